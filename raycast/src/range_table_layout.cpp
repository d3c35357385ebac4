#include "range_table_layout.hpp"

#include <algorithm>
#include <functional>
#include <limits>

#include "mote/core/parallel.hpp"

namespace mote::detail {

namespace {

int blocks_along(int cells, int lattice) { return (cells + lattice - 1) / lattice; }

/// The non-blocking cell of block (bi, bj) nearest to the block's centre (ties: the first in
/// row-major order), or -1 when the block has none.
long representative(const CellMask& mask, int lattice, int bi, int bj) {
  const int i0 = bi * lattice;
  const int j0 = bj * lattice;
  const int i1 = std::min(i0 + lattice, mask.width);
  const int j1 = std::min(j0 + lattice, mask.height);
  // Twice the coordinates, to keep the centre of an even block on integers.
  const int ci = i0 + i1 - 1;
  const int cj = j0 + j1 - 1;
  long best = -1;
  int best_d = std::numeric_limits<int>::max();
  for (int j = j0; j < j1; ++j) {
    for (int i = i0; i < i1; ++i) {
      if (mask.blocks(i, j)) continue;
      const int d = (2 * i - ci) * (2 * i - ci) + (2 * j - cj) * (2 * j - cj);
      if (d < best_d) {
        best_d = d;
        best = static_cast<long>(j) * mask.width + i;
      }
    }
  }
  return best;
}

}  // namespace

std::size_t count_free_cells(const CellMask& mask) {
  const std::size_t cells =
      static_cast<std::size_t>(mask.width) * static_cast<std::size_t>(mask.height);
  return par::reduce(
      cells, /*block=*/std::size_t{1} << 20U, std::size_t{0},
      [&](std::size_t begin, std::size_t end) {
        std::size_t n = 0;
        for (std::size_t k = begin; k < end; ++k) n += mask.cells[k] == 0 ? 1 : 0;
        return n;
      },
      std::plus<>());
}

std::size_t count_lattice_points(const CellMask& mask, int lattice) {
  const auto w = static_cast<std::size_t>(mask.width);
  const auto h = static_cast<std::size_t>(mask.height);
  const auto l = static_cast<std::size_t>(lattice);
  // Per row of blocks, the AND of its rows says which columns block throughout (a vector pass
  // over the mask); a block has a free cell where one of its columns does not.
  const auto blocks_in = [&](std::size_t bj0, std::size_t bj1) {
    std::vector<std::uint8_t> all_block(w);
    std::size_t n = 0;
    for (std::size_t bj = bj0; bj < bj1; ++bj) {
      std::fill(all_block.begin(), all_block.end(), std::uint8_t{1});
      for (std::size_t j = bj * l; j < std::min(h, (bj + 1) * l); ++j) {
        const std::uint8_t* row = mask.cells + j * w;
        for (std::size_t i = 0; i < w; ++i) all_block[i] &= row[i];
      }
      for (std::size_t i0 = 0; i0 < w; i0 += l) {
        const std::size_t i1 = std::min(w, i0 + l);
        if (std::find(all_block.begin() + static_cast<std::ptrdiff_t>(i0),
                      all_block.begin() + static_cast<std::ptrdiff_t>(i1),
                      std::uint8_t{0}) != all_block.begin() + static_cast<std::ptrdiff_t>(i1)) {
          ++n;
        }
      }
    }
    return n;
  };
  return par::reduce(static_cast<std::size_t>(blocks_along(mask.height, lattice)), /*block=*/16,
                     std::size_t{0}, blocks_in, std::plus<>());
}

std::size_t table_bytes(std::size_t points, std::size_t blocks, std::size_t cells, int angles) {
  // Ranges (uint16 per point and angle); per point its cell and its coordinates (two floats);
  // the slot of each block; the blocking mask (a byte per cell) for the start rule.
  return points * static_cast<std::size_t>(angles) * sizeof(std::uint16_t) +
         points * (sizeof(std::uint32_t) + 2 * sizeof(float)) + blocks * sizeof(std::uint32_t) +
         cells;
}

TableLayout make_layout(const CellMask& mask, int lattice) {
  TableLayout t;
  t.width = mask.width;
  t.height = mask.height;
  t.lattice = lattice;
  t.blocks_w = blocks_along(mask.width, lattice);
  t.blocks_h = blocks_along(mask.height, lattice);
  t.slot_of_block.assign(
      static_cast<std::size_t>(t.blocks_w) * static_cast<std::size_t>(t.blocks_h), kNoSlot);
  for (int bj = 0; bj < t.blocks_h; ++bj) {
    for (int bi = 0; bi < t.blocks_w; ++bi) {
      const long cell = representative(mask, lattice, bi, bj);
      if (cell < 0) continue;
      t.slot_of_block[static_cast<std::size_t>(bj) * static_cast<std::size_t>(t.blocks_w) +
                      static_cast<std::size_t>(bi)] = static_cast<std::uint32_t>(t.points());
      t.cell_of_slot.push_back(static_cast<std::uint32_t>(cell));
    }
  }
  return t;
}

}  // namespace mote::detail
