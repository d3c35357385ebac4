// The range table against exact Embree casting: on the recorded maps (Intel, Willow, Stata
// basement) for rays from free cells, and exactly for rays from occupied, unknown and off-map
// origins; plus determinism, the memory budget and the lattice fallback.

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "grids.hpp"
#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/grid_ray_caster.hpp"
#include "mote/raycast/range_table.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

constexpr float kMaxRange = 30.0F;

/// Shares of rays from free cells within one and within two cells of Embree, and the 99th
/// percentile (cells), at the default 512 angles on a lattice of every cell. These are the values
/// measured when the table was written (BENCHMARKS.md, "Range table"), kept as floors so a change
/// that makes the table less accurate fails (within two cells: rays that are grossly off, which
/// the p99 alone does not count once most rays are right); issue 19 asked for 99% within one cell,
/// which a 256 MB table of these maps does not reach (the misses are rays grazing walls, see
/// BENCHMARKS.md).
struct Floor {
  const char* map;
  double within_one_cell;
  double within_two_cells;
  double p99_cells;
};

void expect_close_to_embree(const Floor& f) {
  MOTE_REQUIRE_DATA(path, f.map);
  const OccupancyGrid grid = load_map(path);
  // 512 angles on every cell: Willow's 549k free cells need 537 MB, over the default budget.
  const RangeTable table(grid, RangeTableOptions{.memory_budget_bytes = std::size_t{1} << 30U});
  ASSERT_EQ(table.stats().lattice, 1);
  const RayCaster exact(grid);
  const RangeTableAccuracy acc = measure_range_table(table, exact, grid, 100000, kMaxRange, 3);
  std::cout << f.map << ": " << acc.within_one_cell * 100 << "% within 1 cell, "
            << acc.within_two_cells * 100 << "% within 2, median " << acc.median_cells << ", p99 "
            << acc.p99_cells << ", max " << acc.max_cells << " cells at (" << acc.worst_origin.x
            << ", " << acc.worst_origin.y << ") " << acc.worst_angle << " rad; "
            << static_cast<double>(table.stats().bytes) / 1048576.0 << " MB, built in "
            << table.stats().build_seconds << " s\n";
  EXPECT_GE(acc.within_one_cell, f.within_one_cell);
  EXPECT_GE(acc.within_two_cells, f.within_two_cells);
  EXPECT_LE(acc.p99_cells, f.p99_cells);
  EXPECT_LE(acc.median_cells, 0.5);
}

TEST(RangeTable, IntelCloseToEmbree) {
  expect_close_to_embree({"intel/intel.yaml", 0.91, 0.95, 30.0});
}

TEST(RangeTable, WillowCloseToEmbree) {
  expect_close_to_embree({"maps/willow-full-0.05.yaml", 0.91, 0.945, 45.0});
}

TEST(RangeTable, StataBasementCloseToEmbree) {
  expect_close_to_embree({"maps/basement_fixed.map.yaml", 0.87, 0.93, 16.0});
}

/// Rays from occupied and unknown cells and from off the map give what the exact casters give:
/// 0 from a blocking cell, the grid walk's range from off the map.
TEST(RangeTable, BlockedAndOffMapStartsAreExact) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const RangeTable table(grid);
  const RayCaster exact(grid);
  const GridRayCaster walk(grid);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int occupied = 0;
  int unknown = 0;
  for (std::size_t k = 0; k < grid.cell_count(); k += 7) {
    const CellState state = grid.cells()[k];
    if (state == CellState::kFree) continue;
    const auto w = static_cast<std::size_t>(grid.width());
    const Point2 o = grid.to_map_frame({(double(k % w) + u(rng)) * grid.resolution(),
                                        (double(k / w) + u(rng)) * grid.resolution()});
    const double angle = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    EXPECT_EQ(table.cast_one(o, angle, kMaxRange), exact.cast_one(o, angle, kMaxRange));
    (state == CellState::kOccupied ? occupied : unknown) += 1;
  }
  EXPECT_GT(occupied, 1000);
  EXPECT_GT(unknown, 1000);
  const double w = grid.width() * grid.resolution();
  for (int k = 0; k < 2000; ++k) {  // off the map, within 5 m of it, on the left or right
    const double gx = u(rng) < 0.5 ? -5.0 * u(rng) - 0.01 : w + 5.0 * u(rng) + 0.01;
    const Point2 o = grid.to_map_frame({gx, u(rng) * grid.height() * grid.resolution()});
    const double angle = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    EXPECT_EQ(table.cast_one(o, angle, kMaxRange), walk.cast_one(o, angle, kMaxRange));
  }
}

/// Same table and same batch ranges on 1 and 2 threads.
TEST(RangeTable, SameOnAnyThreadCount) {
  const OccupancyGrid grid = test::box_room();
  RangeTableOptions options;
  options.angles = 64;
  options.particle_grain = 16;
  std::vector<float> x, y, theta, beams{-1.0F, 0.0F, 0.5F, 3.0F};
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<float> u(0.0F, 1.0F);
  for (int i = 0; i < 300; ++i) {
    x.push_back(-1.0F + 7.0F * u(rng));
    y.push_back(-1.0F + 7.0F * u(rng));
    theta.push_back(6.0F * u(rng) - 3.0F);
  }
  const RayBatch batch{x, y, theta, beams, Pose2{0.1, 0.0, 0.0}, 10.0F};
  std::vector<std::vector<float>> out;
  for (const int threads : {1, 2}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      const RangeTable table(grid, options);
      out.emplace_back(batch.ray_count());
      table.cast(batch, out.back());
    });
  }
  EXPECT_EQ(out[0], out[1]);
  // A batch gives what single rays give.
  const RangeTable table(grid, options);
  for (std::size_t p = 0; p < x.size(); p += 37) {
    const double c = std::cos(theta[p]);
    const double s = std::sin(theta[p]);
    const Point2 sensor{x[p] + 0.1 * c, y[p] + 0.1 * s};
    for (std::size_t b = 0; b < beams.size(); ++b) {
      EXPECT_NEAR(out[0][p * beams.size() + b], table.cast_one(sensor, theta[p] + beams[b], 10.0F),
                  1e-4);
    }
  }
}

/// In the box room (inner faces at 0.5 m and 4.5 m) a ray along an axis from a cell centre
/// reads the exact distance to the face.
TEST(RangeTable, AxisRaysInTheBoxRoom) {
  const OccupancyGrid grid = test::box_room();
  const RangeTable table(grid, RangeTableOptions{.angles = 64});
  const Point2 centre{1.75, 2.25};
  EXPECT_NEAR(table.cast_one(centre, 0.0, 10.0F), 4.5 - 1.75, 1e-3);
  EXPECT_NEAR(table.cast_one(centre, std::numbers::pi, 10.0F), 1.75 - 0.5, 1e-3);
  EXPECT_NEAR(table.cast_one(centre, std::numbers::pi / 2, 10.0F), 4.5 - 2.25, 1e-3);
  EXPECT_NEAR(table.cast_one(centre, -std::numbers::pi / 2, 10.0F), 2.25 - 0.5, 1e-3);
  EXPECT_NEAR(table.cast_one(centre, 0.0, 1.0F), 1.0F, 1e-6) << "clamped to max_range";
}

/// A finite but huge ray angle (its wrap into the table's angles loses every digit) still reads
/// a range in [0, max_range], with 96 angles, where 2 pi / 96 is no power of two (the UBSan
/// job would report a float-to-int overflow before the angle index was reduced).
TEST(RangeTable, HugeAnglesStayInRange) {
  const OccupancyGrid grid = test::box_room();
  const RangeTable table(grid, RangeTableOptions{.angles = 96});
  for (const double angle : {1e25, -3e30, 7e300}) {
    const float r = table.cast_one({1.75, 2.25}, angle, 10.0F);
    EXPECT_TRUE(r >= 0.0F && r <= 10.0F) << angle << " read " << r;
  }
}

/// A batch of particles in Intel's free cells reads what single rays read, beam by beam: the
/// batch chooses lattice points for all beams of a sensor at once (vectorized), cast_one one
/// ray at a time, and both must make the same choice. Also on a coarser lattice (3 cells at a
/// 40 MB budget), where the chosen points are not cell centres.
TEST(RangeTable, BatchMatchesSingleRaysOnIntel) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  std::vector<float> beams;
  for (int b = 0; b < 61; ++b) beams.push_back(static_cast<float>(-1.5 + 0.05 * b));
  const auto [x, y, theta] = test::scatter_in_free_cells(grid, 1500, 11);
  const RayBatch batch{x, y, theta, beams, Pose2{}, kMaxRange};
  for (const std::size_t budget_mb : {std::size_t{256}, std::size_t{40}}) {
    const RangeTable table(grid, RangeTableOptions{.memory_budget_bytes = budget_mb << 20U});
    ASSERT_EQ(table.stats().lattice, budget_mb == 256 ? 1 : 3);
    std::vector<float> out(batch.ray_count());
    table.cast(batch, out);
    std::size_t far = 0;
    for (std::size_t p = 0; p < x.size(); ++p) {
      for (std::size_t b = 0; b < beams.size(); ++b) {
        const float single = table.cast_one({x[p], y[p]}, double(theta[p]) + beams[b], kMaxRange);
        // Written so that a NaN on either side counts as a difference.
        if (!(std::abs(out[p * beams.size() + b] - single) <= 1e-3F)) ++far;
      }
    }
    // The two compute the table angle index from the same angle by different roundings
    // (heading and beam indices added, against one index), so a ray within rounding of
    // half-way between two table angles may round to either; none did when this was written
    // (0 of 91500 on both lattices), one in 10^4 is the allowance. Choosing the sensor's own
    // point for every beam in the batch makes 55 % of the rays differ.
    EXPECT_LE(far, batch.ray_count() / 10000)
        << far << " of " << batch.ray_count() << " rays differ, lattice " << table.stats().lattice;
  }
}

TEST(RangeTable, CoarserLatticeWhenOverBudgetAndErrorWhenNothingFits) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  RangeTableOptions options;
  options.angles = 64;
  options.memory_budget_bytes = std::size_t{8} << 20U;  // every cell would need 24 MB
  const RangeTable table(grid, options);
  EXPECT_GT(table.stats().lattice, 1);
  EXPECT_LE(table.stats().bytes, options.memory_budget_bytes);
  options.memory_budget_bytes = 1000;
  try {
    const RangeTable none(grid, options);
    ADD_FAILURE() << "a 1000-byte budget built a table";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("needs"), std::string::npos) << e.what();
  }
  options.angles = 48;
  EXPECT_THROW(RangeTable(grid, options), ConfigError) << "angles not a multiple of 32";
}

}  // namespace
}  // namespace mote
