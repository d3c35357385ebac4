// The linear-time distance transform against a brute-force one on random grids.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/likelihood_table.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

OccupancyGrid random_grid(std::mt19937& rng, int w, int h, double occupied, double unknown) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<CellState> cells(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (CellState& c : cells) {
    const double r = u(rng);
    c = r < occupied ? CellState::kOccupied
                     : (r < occupied + unknown ? CellState::kUnknown : CellState::kFree);
  }
  return {w, h, 0.05, Pose2{1.0, -2.0, 0.3}, std::move(cells)};
}

/// min over obstacle cells of the centre-to-centre distance, computed as the transform does.
std::vector<float> brute_force(const OccupancyGrid& g, const DistanceFieldOptions& o) {
  std::vector<CellIndex> obstacles;
  for (int b = 0; b < g.height(); ++b) {
    for (int a = 0; a < g.width(); ++a) {
      const CellState s = g.at({a, b});
      if (s == CellState::kOccupied || (o.unknown_is_obstacle && s == CellState::kUnknown)) {
        obstacles.push_back({a, b});
      }
    }
  }
  std::vector<float> out;
  for (int j = 0; j < g.height(); ++j) {
    for (int i = 0; i < g.width(); ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (const CellIndex c : obstacles) {
        const double di = i - c.i;
        const double dj = j - c.j;
        best = std::min(best, di * di + dj * dj);
      }
      out.push_back(std::min(static_cast<float>(std::sqrt(best) * g.resolution()), o.max_distance));
    }
  }
  return out;
}

TEST(DistanceField, EqualsBruteForceOnRandomGrids) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> size(1, 24);
  std::uniform_real_distribution<double> density(0.0, 0.3);
  for (int trial = 0; trial < 300; ++trial) {
    const OccupancyGrid grid = random_grid(rng, size(rng), size(rng), density(rng), density(rng));
    DistanceFieldOptions options;
    options.unknown_is_obstacle = trial % 2 == 1;
    if (trial % 3 == 0) options.max_distance = 0.2F;
    const DistanceField field(grid, options);
    ASSERT_EQ(field.distances(), brute_force(grid, options)) << "trial " << trial;
  }
}

TEST(DistanceField, SparseObstaclesFarApart) {
  std::vector<CellState> cells(60 * 45, CellState::kFree);
  cells[3] = cells[44 * 60 + 59] = cells[20 * 60 + 31] = CellState::kOccupied;
  const OccupancyGrid grid(60, 45, 0.1, Pose2{}, cells);
  const DistanceField field(grid);
  EXPECT_EQ(field.distances(), brute_force(grid, {}));
  EXPECT_FLOAT_EQ(field.at({0, 0}), 0.3F);
  EXPECT_FLOAT_EQ(field.at({31, 20}), 0.0F);
}

TEST(DistanceField, NoObstacleGivesInfinityOrTheClamp) {
  const OccupancyGrid grid(7, 5, 0.1, Pose2{}, std::vector<CellState>(35, CellState::kUnknown));
  const DistanceField plain(grid);
  for (const float d : plain.distances()) EXPECT_EQ(d, std::numeric_limits<float>::infinity());
  const DistanceField clamped(grid, {.unknown_is_obstacle = false, .max_distance = 2.5F});
  for (const float d : clamped.distances()) EXPECT_EQ(d, 2.5F);
  const DistanceField unknown(grid, {.unknown_is_obstacle = true});
  for (const float d : unknown.distances()) EXPECT_EQ(d, 0.0F);
}

TEST(DistanceField, KeepsTheGridGeometry) {
  std::mt19937 rng(1);
  const OccupancyGrid grid = random_grid(rng, 9, 4, 0.2, 0.0);
  const DistanceField field(grid);
  EXPECT_EQ(field.width(), 9);
  EXPECT_EQ(field.height(), 4);
  EXPECT_EQ(field.resolution(), 0.05);
  EXPECT_EQ(field.origin().theta, 0.3);
}

TEST(DistanceField, RejectsBadClamp) {
  std::mt19937 rng(1);
  const OccupancyGrid grid = random_grid(rng, 3, 3, 0.2, 0.0);
  EXPECT_THROW(DistanceField(grid, {.max_distance = -1.0F}), ConfigError);
  EXPECT_THROW(DistanceField(grid, {.max_distance = std::nanf("")}), ConfigError);
}

TEST(DistanceField, SameOnOneAndTwoThreadsAndEqualsBruteForce) {
  std::mt19937 rng(3);
  const OccupancyGrid grid = random_grid(rng, 613, 171, 0.002, 0.1);
  tbb::task_arena one(1);
  tbb::task_arena two(2);
  std::vector<float> a;
  std::vector<float> b;
  one.execute([&] { a = DistanceField(grid).distances(); });
  two.execute([&] { b = DistanceField(grid).distances(); });
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, brute_force(grid, {}));
}

TEST(DistanceField, RecordedMapSpotChecksAgainstBruteForce) {
  MOTE_REQUIRE_DATA(path, "maps/basement_fixed.map.yaml");
  const OccupancyGrid grid = load_map(path);
  const DistanceField field(grid);
  std::vector<CellIndex> walls;
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      if (grid.at({i, j}) == CellState::kOccupied) walls.push_back({i, j});
    }
  }
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> col(0, grid.width() - 1);
  std::uniform_int_distribution<int> row(0, grid.height() - 1);
  for (int k = 0; k < 200; ++k) {
    const CellIndex c{col(rng), row(rng)};
    double best = std::numeric_limits<double>::infinity();
    for (const CellIndex w : walls) {
      best = std::min(best, std::pow(c.i - w.i, 2.0) + std::pow(c.j - w.j, 2.0));
    }
    ASSERT_EQ(field.at(c), static_cast<float>(std::sqrt(best) * grid.resolution()));
  }
  // The table on the yawed map reads each wall cell's own value at its centre.
  const LikelihoodTable table(
      field, [](float d) { return -d; }, 1.0F);
  for (std::size_t k = 0; k < walls.size(); k += 97) {
    const Point2 p = grid.cell_center(walls[k]);
    EXPECT_EQ(table.lookup(static_cast<float>(p.x), static_cast<float>(p.y)), -0.0F);
  }
}

}  // namespace
}  // namespace mote
