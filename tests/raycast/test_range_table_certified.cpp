// The range tables that cast some rays exactly: certified (RangeTableOptions::certify: entries
// that cannot vouch for their rays within a cell send those rays to Embree) and confirmed
// (::confirm: every ray's range is a wall face its neighbours' entries name, confirmed on the
// map, the unconfirmed rays sent to Embree). Issue 19's accuracy target (99 % of rays from free
// cells within one cell of Embree) on Intel, Willow and Stata basement, plus the contracts the
// plain table keeps: determinism, blocked and off-map starts.

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <vector>

#include "grids.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/grid_ray_caster.hpp"
#include "mote/raycast/range_table.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

constexpr float kMaxRange = 30.0F;

RangeTableOptions certified(std::size_t budget_mb = 256) {
  return {.memory_budget_bytes = budget_mb << 20U, .certify = true};
}

RangeTableOptions confirmed(std::size_t budget_mb = 256) {
  return {.memory_budget_bytes = budget_mb << 20U, .confirm = true};
}

/// 99 % within one cell is issue 19's target; p99 at most a cell follows from it. The seed is
/// fixed, so the shares are the same on every run (certified: Intel 99.04 %, Willow 99.07 %,
/// Stata basement 99.32 %; confirmed: 99.20 %, 99.25 %, 99.18 % when written: BENCHMARKS.md,
/// "Range table").
void expect_99_percent_within_one_cell(const char* map, const RangeTableOptions& options) {
  MOTE_REQUIRE_DATA(path, map);
  const OccupancyGrid grid = load_map(path);
  const RangeTable table(grid, options);
  ASSERT_EQ(table.stats().lattice, 1);
  const RayCaster exact(grid);
  const RangeTableAccuracy acc = measure_range_table(table, exact, grid, 100000, kMaxRange, 3);
  std::cout << map << ": " << acc.within_one_cell * 100 << "% within 1 cell, "
            << acc.within_two_cells * 100 << "% within 2, p99 " << acc.p99_cells << ", max "
            << acc.max_cells << " cells at (" << acc.worst_origin.x << ", " << acc.worst_origin.y
            << ") " << acc.worst_angle << " rad; " << table.stats().uncertified * 100
            << "% of entries uncertified (certified tables), built in "
            << table.stats().build_seconds << " s\n";
  EXPECT_GE(acc.within_one_cell, 0.99);
  EXPECT_LE(acc.p99_cells, 1.0);
  if (options.certify) {
    EXPECT_GT(table.stats().uncertified, 0.0);
  }
}

TEST(RangeTableCertified, IntelWithinOneCell) {
  expect_99_percent_within_one_cell("intel/intel.yaml", certified(1024));
}
TEST(RangeTableCertified, WillowWithinOneCell) {
  expect_99_percent_within_one_cell("maps/willow-full-0.05.yaml", certified(1024));
}
TEST(RangeTableCertified, StataBasementWithinOneCell) {
  expect_99_percent_within_one_cell("maps/basement_fixed.map.yaml", certified(1024));
}
TEST(RangeTableConfirmed, IntelWithinOneCell) {
  expect_99_percent_within_one_cell("intel/intel.yaml", confirmed(1024));
}
TEST(RangeTableConfirmed, WillowWithinOneCell) {
  expect_99_percent_within_one_cell("maps/willow-full-0.05.yaml", confirmed(1024));
}
TEST(RangeTableConfirmed, StataBasementWithinOneCell) {
  expect_99_percent_within_one_cell("maps/basement_fixed.map.yaml", confirmed(1024));
}

/// Rays from occupied and unknown cells read 0 and rays from off the map the grid walk's range,
/// as with exact casting; the Embree scene the table keeps is counted in its bytes.
void expect_blocked_and_off_map_starts_exact(const RangeTableOptions& options) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const RangeTable table(grid, options);
  const RayCaster exact(grid);
  const GridRayCaster walk(grid);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto w = static_cast<std::size_t>(grid.width());
  for (std::size_t k = 0; k < grid.cell_count(); k += 7) {
    if (grid.cells()[k] == CellState::kFree) continue;
    const Point2 o = grid.to_map_frame({(double(k % w) + u(rng)) * grid.resolution(),
                                        (double(k / w) + u(rng)) * grid.resolution()});
    const double angle = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    EXPECT_EQ(table.cast_one(o, angle, kMaxRange), exact.cast_one(o, angle, kMaxRange));
  }
  for (int k = 0; k < 2000; ++k) {
    const double gx = -5.0 * u(rng) - 0.01;
    const Point2 o = grid.to_map_frame({gx, u(rng) * grid.height() * grid.resolution()});
    const double angle = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    EXPECT_EQ(table.cast_one(o, angle, kMaxRange), walk.cast_one(o, angle, kMaxRange));
  }
  const RangeTable plain(grid);
  EXPECT_GT(table.stats().bytes, plain.stats().bytes);
  EXPECT_LE(table.stats().bytes, std::size_t{256} << 20U);
}

TEST(RangeTableCertified, BlockedAndOffMapStartsAreExact) {
  expect_blocked_and_off_map_starts_exact(certified());
}
TEST(RangeTableConfirmed, BlockedAndOffMapStartsAreExact) {
  expect_blocked_and_off_map_starts_exact(confirmed());
}

/// Particles in Intel's free cells and around them: the same ranges on 1 and 2 threads (the
/// exact rays are packed by particle index within chunks of the grain), and what single rays
/// read, beam by beam, up to rays within rounding of a table angle (see the plain table's test).
void expect_same_on_any_thread_count_and_as_single_rays(const RangeTableOptions& options) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  std::vector<float> beams;
  for (int b = 0; b < 61; ++b) beams.push_back(static_cast<float>(-1.5 + 0.05 * b));
  const auto [x, y, theta] = test::scatter_in_free_cells(grid, 1000, 13, 10);
  const RayBatch batch{x, y, theta, beams, Pose2{}, kMaxRange};
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
  const RangeTable table(grid, options);
  std::size_t far = 0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    for (std::size_t b = 0; b < beams.size(); ++b) {
      const float single = table.cast_one({x[p], y[p]}, double(theta[p]) + beams[b], kMaxRange);
      if (!(std::abs(out[0][p * beams.size() + b] - single) <= 1e-3F)) ++far;
    }
  }
  EXPECT_LE(far, batch.ray_count() / 10000) << far << " of " << batch.ray_count() << " differ";
}

TEST(RangeTableCertified, SameOnAnyThreadCountAndAsSingleRays) {
  expect_same_on_any_thread_count_and_as_single_rays(certified());
}
TEST(RangeTableConfirmed, SameOnAnyThreadCountAndAsSingleRays) {
  expect_same_on_any_thread_count_and_as_single_rays(confirmed());
}

}  // namespace
}  // namespace mote
