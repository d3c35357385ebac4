#pragma once
// The pieces of the saturated transform its two implementations share (squared_distances.cpp:
// the envelope over a full-size array; squared_rows.cpp: a band of rows at a time). Internal.

#include <cstddef>
#include <cstdint>

#include "mote/maps/occupancy_grid.hpp"
#include "mote/maps/squared_distances.hpp"

namespace mote::detail {

/// The obstacle test of one rule at cell (i, j) of a w x h grid, row-major from the bottom row.
template <ObstacleCells Rule>
bool obstacle(const CellState* cells, std::size_t w, std::size_t h, std::size_t i,
              std::size_t j) noexcept {
  const CellState s = cells[j * w + i];
  if constexpr (Rule == ObstacleCells::kOccupied) return s == CellState::kOccupied;
  if constexpr (Rule == ObstacleCells::kOccupiedOrUnknown) return s != CellState::kFree;
  if constexpr (Rule == ObstacleCells::kNotOccupied) return s != CellState::kOccupied;
  if constexpr (Rule == ObstacleCells::kSurface) {
    if (s != CellState::kOccupied) return false;
    const CellState* c = cells + j * w + i;
    return (i > 0 && c[-1] == CellState::kFree) || (i + 1 < w && c[1] == CellState::kFree) ||
           (j > 0 && c[-static_cast<std::ptrdiff_t>(w)] == CellState::kFree) ||
           (j + 1 < h && c[w] == CellState::kFree);
  }
  return false;
}

/// The whole transform into out (width * height values, min(exact, saturation^2)) by columns
/// then the envelope along rows: any saturation up to SquaredDistances::kMaxSaturation.
void envelope_squared_distances(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
                                std::uint16_t* out);

}  // namespace mote::detail
