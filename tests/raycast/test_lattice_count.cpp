// The range table's lattice is chosen by counting its points before building it: the count
// (rows of blocks ANDed in vector passes, in parallel) must equal the blocks that hold a
// non-blocking cell, and the free-cell bound under it must hold, on random masks of awkward
// sizes and on Intel's map, for any thread count.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cstdint>
#include <random>
#include <vector>

#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"
#include "range_table_layout.hpp"
#include "ray_setup.hpp"

namespace mote {
namespace {

using detail::CellMask;

/// The definition, one block at a time.
std::size_t blocks_with_a_free_cell(const CellMask& mask, int lattice) {
  std::size_t n = 0;
  for (int bj = 0; bj * lattice < mask.height; ++bj) {
    for (int bi = 0; bi * lattice < mask.width; ++bi) {
      bool free = false;
      for (int j = bj * lattice; j < std::min(mask.height, (bj + 1) * lattice); ++j) {
        for (int i = bi * lattice; i < std::min(mask.width, (bi + 1) * lattice); ++i) {
          free = free || !mask.blocks(i, j);
        }
      }
      n += free ? 1 : 0;
    }
  }
  return n;
}

void expect_counts(const CellMask& mask, int lattice) {
  const std::size_t expected = blocks_with_a_free_cell(mask, lattice);
  for (const int threads : {1, 2}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      EXPECT_EQ(detail::count_lattice_points(mask, lattice), expected)
          << mask.width << " x " << mask.height << ", lattice " << lattice << ", " << threads
          << " threads";
    });
  }
  const std::size_t area = static_cast<std::size_t>(lattice) * static_cast<std::size_t>(lattice);
  EXPECT_LE((detail::count_free_cells(mask) + area - 1) / area, expected) << "the lower bound";
}

TEST(LatticeCount, EqualsTheBlocksHoldingAFreeCellOnRandomMasks) {
  std::mt19937 rng(7);
  for (const auto& [w, h] : {std::pair{1, 1}, {37, 5}, {130, 97}, {301, 260}}) {
    // Mostly blocking, so that whole blocks block and the count differs from the block count.
    for (const double p_free : {0.0, 0.002, 0.05, 1.0}) {
      std::bernoulli_distribution free(p_free);
      std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
      for (auto& c : cells) c = free(rng) ? 0 : 1;
      const CellMask mask{w, h, 0.05F, cells.data()};
      for (const int lattice : {1, 2, 3, 7, 16, 40}) expect_counts(mask, lattice);
    }
  }
}

TEST(LatticeCount, EqualsTheBlocksHoldingAFreeCellOnIntel) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  for (const bool unknown_blocks : {false, true}) {
    const std::vector<std::uint8_t> cells = detail::blocking_mask(grid, unknown_blocks);
    const CellMask mask{grid.width(), grid.height(), static_cast<float>(grid.resolution()),
                        cells.data()};
    for (const int lattice : {1, 3, 5, 19}) expect_counts(mask, lattice);
  }
}

}  // namespace
}  // namespace mote
