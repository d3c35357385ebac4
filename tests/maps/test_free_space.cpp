// OccupancyGrid as FreeSpace: the free-cell index, points drawn in free cells, bounds.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <random>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {
namespace {

OccupancyGrid random_grid(std::uint32_t seed, Pose2 origin, int w = 23, int h = 17) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> state(0, 2);
  std::vector<CellState> cells(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (CellState& c : cells) c = static_cast<CellState>(state(rng));
  return {w, h, 0.25, origin, std::move(cells)};
}

std::vector<std::uint32_t> serial_free_index(const OccupancyGrid& grid) {
  std::vector<std::uint32_t> expected;
  for (std::uint32_t k = 0; k < grid.cell_count(); ++k) {
    if (grid.cells()[k] == CellState::kFree) expected.push_back(k);
  }
  return expected;
}

TEST(FreeSpace, IndexListsExactlyTheFreeCellsInOrder) {
  const OccupancyGrid grid = random_grid(5, Pose2{});
  EXPECT_EQ(grid.free_cells(), serial_free_index(grid));
  EXPECT_EQ(grid.free_cell_count(), serial_free_index(grid).size());
}

TEST(FreeSpace, IndexOverManyBlocksOnTwoThreads) {
  // 701 x 303 cells span many blocks of the index and of the parallel listing, the last partial.
  tbb::task_arena two(2);
  two.execute([] {
    const OccupancyGrid grid = random_grid(8, Pose2{}, 701, 303);
    EXPECT_EQ(grid.free_cells(), serial_free_index(grid));
  });
}

TEST(FreeSpace, TheKthFreeCellOfTheBlockIndexIsTheListsKth) {
  // 701 x 303 cells: many 64-cell blocks, some without a free cell, the last one partial.
  const OccupancyGrid grid = random_grid(4, Pose2{}, 701, 303);
  const std::vector<std::uint32_t> expected = serial_free_index(grid);
  ASSERT_EQ(grid.free_cell_count(), expected.size());
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    mismatches += grid.free_cell(k) == expected[k] ? 0U : 1U;
  }
  EXPECT_EQ(mismatches, 0U);
}

TEST(FreeSpace, DrawnPointsFallInTheirFreeCell) {
  for (const double yaw : {0.0, 0.9, 3.14, -1.6}) {
    const OccupancyGrid grid = random_grid(9, Pose2{2.0, -1.0, yaw});
    const FreeSpace& space = grid;
    const std::vector<std::uint32_t> free = grid.free_cells();
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(0.01, 0.99);
    for (std::size_t k = 0; k < space.free_cell_count(); ++k) {
      const Point2 p = space.free_point(k, u(rng), u(rng));
      const CellIndex c = grid.world_to_cell(p);
      ASSERT_TRUE(grid.contains(c));
      EXPECT_EQ(grid.linear_index(c), free[k]);
      EXPECT_EQ(grid.at(c), CellState::kFree);
    }
  }
}

TEST(FreeSpace, CornersOfTheFreePointSpanTheCell) {
  std::vector<CellState> cells(4, CellState::kOccupied);
  cells[3] = CellState::kFree;  // cell (1, 1)
  const OccupancyGrid grid(2, 2, 0.5, Pose2{10.0, 20.0, 0.0}, cells);
  ASSERT_EQ(grid.free_cell_count(), 1U);
  EXPECT_DOUBLE_EQ(grid.free_point(0, 0.0, 0.0).x, 10.5);
  EXPECT_DOUBLE_EQ(grid.free_point(0, 0.0, 0.0).y, 20.5);
  EXPECT_DOUBLE_EQ(grid.free_point(0, 1.0, 1.0).x, 11.0);
  EXPECT_DOUBLE_EQ(grid.free_point(0, 1.0, 1.0).y, 21.0);
}

TEST(FreeSpace, BoundsHoldEveryCellCentre) {
  const OccupancyGrid grid = random_grid(3, Pose2{-4.0, 6.0, 0.6});
  const Bounds2 b = grid.bounds();
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      const Point2 p = grid.cell_center({i, j});
      EXPECT_TRUE(p.x > b.min_x && p.x < b.max_x && p.y > b.min_y && p.y < b.max_y);
    }
  }
}

TEST(FreeSpace, NoFreeCellsMeansNowhereToBe) {
  const OccupancyGrid grid(2, 1, 0.1, Pose2{}, {CellState::kOccupied, CellState::kUnknown});
  EXPECT_EQ(grid.free_cell_count(), 0U);
}

TEST(OccupancyGrid, RejectsBadShapes) {
  EXPECT_THROW(OccupancyGrid(0, 1, 0.1, Pose2{}, {}), ConfigError);
  EXPECT_THROW(OccupancyGrid(1, 1, 0.0, Pose2{}, {CellState::kFree}), ConfigError);
  EXPECT_THROW(OccupancyGrid(2, 1, 0.1, Pose2{}, {CellState::kFree}), ConfigError);
}

}  // namespace
}  // namespace mote
