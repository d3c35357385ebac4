#pragma once
/// \file
/// Internal: where the range table's lattice points are and how many bytes a lattice takes.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ray_setup.hpp"

namespace mote::detail {

/// No lattice point (a block of blocking cells only).
inline constexpr std::uint32_t kNoSlot = 0xFFFFFFFFU;

/// The lattice of a range table: the map is cut into blocks of lattice x lattice cells, and every
/// block holding a non-blocking cell gets one lattice point (a slot), placed at the centre of the
/// non-blocking cell nearest to the block's centre (so a lattice point never sits in a wall).
struct TableLayout {
  int width = 0;   ///< cells
  int height = 0;  ///< cells
  int lattice = 1;
  int blocks_w = 0;
  int blocks_h = 0;
  std::vector<std::uint32_t> slot_of_block;  ///< row-major from the bottom, kNoSlot when none
  std::vector<std::uint32_t> cell_of_slot;   ///< linear cell index of each slot's point

  [[nodiscard]] std::size_t points() const noexcept { return cell_of_slot.size(); }
  [[nodiscard]] std::uint32_t slot_of_cell(int i, int j) const noexcept {
    return slot_of_block[static_cast<std::size_t>(j / lattice) *
                             static_cast<std::size_t>(blocks_w) +
                         static_cast<std::size_t>(i / lattice)];
  }
};

/// Cells that do not block: with a lattice of l cells, at least ceil(free / l^2) points.
[[nodiscard]] std::size_t count_free_cells(const CellMask& mask);

/// Lattice points of a lattice without building it.
[[nodiscard]] std::size_t count_lattice_points(const CellMask& mask, int lattice);

/// Bytes a table holds: `points` lattice points at `angles` directions, its index over `blocks`
/// blocks and its copy of the blocking state of `cells` cells.
[[nodiscard]] std::size_t table_bytes(std::size_t points, std::size_t blocks, std::size_t cells,
                                      int angles);

/// Builds the lattice.
[[nodiscard]] TableLayout make_layout(const CellMask& mask, int lattice);

}  // namespace mote::detail
