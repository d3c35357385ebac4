#include "range_table_layout.hpp"

#include <algorithm>
#include <limits>

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

bool block_has_free_cell(const CellMask& mask, int lattice, int bi, int bj) {
  const int i1 = std::min((bi + 1) * lattice, mask.width);
  const int j1 = std::min((bj + 1) * lattice, mask.height);
  for (int j = bj * lattice; j < j1; ++j) {
    for (int i = bi * lattice; i < i1; ++i) {
      if (!mask.blocks(i, j)) return true;
    }
  }
  return false;
}

}  // namespace

std::size_t count_lattice_points(const CellMask& mask, int lattice) {
  std::size_t n = 0;
  for (int bj = 0; bj < blocks_along(mask.height, lattice); ++bj) {
    for (int bi = 0; bi < blocks_along(mask.width, lattice); ++bi) {
      if (block_has_free_cell(mask, lattice, bi, bj)) ++n;
    }
  }
  return n;
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
