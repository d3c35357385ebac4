// The likelihood table: grid cells hold f(distance), everything off the map reads `outside`,
// and lookup agrees with OccupancyGrid::world_to_cell.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/likelihood_table.hpp"

namespace mote {
namespace {

constexpr float kOutside = -99.0F;

OccupancyGrid grid_with_walls(Pose2 origin) {
  std::vector<CellState> cells(40 * 30, CellState::kFree);
  for (int i = 5; i < 35; ++i) cells[static_cast<std::size_t>(10 * 40 + i)] = CellState::kOccupied;
  cells[25 * 40 + 3] = CellState::kOccupied;
  cells[0] = CellState::kUnknown;
  return {40, 30, 0.1, origin, std::move(cells)};
}

/// A value that identifies the distance, so any mix-up of cells shows.
float f(float d) { return std::log1p(d) + 0.5F; }

class Table : public ::testing::TestWithParam<double> {};

TEST_P(Table, CellCentresReadTheirOwnDistance) {
  const OccupancyGrid grid = grid_with_walls(Pose2{-3.0, 7.5, GetParam()});
  const DistanceField field(grid);
  const LikelihoodTable table(field, f, kOutside, 2);
  EXPECT_EQ(table.width(), 44);
  EXPECT_EQ(table.height(), 34);
  EXPECT_GE(table.stride(), 44U);
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      const Point2 p = grid.cell_center({i, j});
      ASSERT_EQ(table.lookup(static_cast<float>(p.x), static_cast<float>(p.y)), f(field.at({i, j})))
          << i << ", " << j;
      ASSERT_EQ(table.at({i, j}), f(field.at({i, j})));
    }
  }
}

TEST_P(Table, PointsOffTheMapReadOutside) {
  const OccupancyGrid grid = grid_with_walls(Pose2{-3.0, 7.5, GetParam()});
  const LikelihoodTable table(DistanceField(grid), f, kOutside);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const float far : {1e30F, -1e30F, 1e6F, -1e6F, inf, -inf, nan}) {
    EXPECT_EQ(table.lookup(far, 7.5F), kOutside) << far;
    EXPECT_EQ(table.lookup(-3.0F, far), kOutside) << far;
    EXPECT_EQ(table.lookup(far, far), kOutside) << far;
  }
  // Half a cell past each edge, in the grid frame.
  for (const Point2 g : {Point2{-0.05, 1.5}, Point2{4.05, 1.5}, Point2{2.0, -0.05},
                         Point2{2.0, 3.05}, Point2{-7.0, -9.0}, Point2{40.0, 33.0}}) {
    const Point2 p = grid.to_map_frame(g);
    EXPECT_EQ(table.lookup(static_cast<float>(p.x), static_cast<float>(p.y)), kOutside);
  }
}

TEST_P(Table, AgreesWithWorldToCellOnRandomPoints) {
  const OccupancyGrid grid = grid_with_walls(Pose2{-3.0, 7.5, GetParam()});
  const DistanceField field(grid);
  const LikelihoodTable table(field, f, kOutside);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 5.0);
  int checked = 0;
  for (int k = 0; k < 5000; ++k) {
    const Point2 g{u(rng), u(rng)};
    // Skip points within float rounding of a cell edge, where float and double may disagree.
    const double fx = g.x / 0.1 - std::floor(g.x / 0.1);
    const double fy = g.y / 0.1 - std::floor(g.y / 0.1);
    if (std::min({fx, 1 - fx, fy, 1 - fy}) < 1e-3) continue;
    const Point2 p = grid.to_map_frame(g);
    const CellIndex c = grid.world_to_cell(p);
    const float expected = grid.contains(c) ? f(field.at(c)) : kOutside;
    ASSERT_EQ(table.lookup(static_cast<float>(p.x), static_cast<float>(p.y)), expected);
    ++checked;
  }
  EXPECT_GT(checked, 4500);
}

INSTANTIATE_TEST_SUITE_P(Yaw, Table, ::testing::Values(0.0, 0.7, 3.14, -2.0));

TEST(LikelihoodTable, TransformMatchesTheGrid) {
  const OccupancyGrid grid = grid_with_walls(Pose2{1.0, 2.0, 0.0});
  const LikelihoodTable table(DistanceField(grid), f, kOutside, 3);
  const TableTransform& t = table.transform();
  EXPECT_FLOAT_EQ(t.inv_resolution, 10.0F);
  EXPECT_FLOAT_EQ(t.border, 3.0F);
  EXPECT_FLOAT_EQ(t.max_col, 45.0F);
  EXPECT_FLOAT_EQ(t.max_row, 35.0F);
  EXPECT_EQ(table.data()[0], kOutside);
  EXPECT_EQ(table.data()[3 * table.stride() + 3], table.at({0, 0}));
}

TEST(LikelihoodTable, MapWithoutObstaclesPassesInfinityToF) {
  const OccupancyGrid grid(3, 2, 0.5, Pose2{}, std::vector<CellState>(6, CellState::kFree));
  const LikelihoodTable table(
      DistanceField(grid), [](float d) { return std::isinf(d) ? 1.0F : 0.0F; }, kOutside);
  EXPECT_EQ(table.lookup(0.75F, 0.25F), 1.0F);
  EXPECT_THROW(LikelihoodTable(DistanceField(grid), f, kOutside, 0), ConfigError);
}

}  // namespace
}  // namespace mote
