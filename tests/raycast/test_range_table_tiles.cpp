// Range tables built in tiles on first use (maps whose whole table is over budget): the same
// ranges as the whole table wherever a tile is resident, through builds and evictions; exact
// casting for sensors whose tiles the budget cannot hold; the same on 1 and 2 threads.

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <cstddef>
#include <iostream>
#include <vector>

#include "grids.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/range_table.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

constexpr float kMaxRange = 30.0F;

/// Intel at 64 angles: the whole table on every cell takes about 24 MB, so an 8 MB budget
/// tiles it (a tile is 64 x 64 cells x 64 angles, 512 KB).
RangeTableOptions tiled_options() {
  RangeTableOptions o;
  o.angles = 64;
  o.memory_budget_bytes = std::size_t{8} << 20U;
  return o;
}

RangeTableOptions whole_options() {
  RangeTableOptions o = tiled_options();
  o.memory_budget_bytes = std::size_t{1} << 30U;
  return o;
}

const std::vector<float>& beams() {
  static const std::vector<float> b = [] {
    std::vector<float> v;
    for (int k = 0; k < 24; ++k) v.push_back(static_cast<float>(-3.0 + 0.25 * k));
    return v;
  }();
  return b;
}

/// The poses of `all` within `half` m (in x and y) of pose c: a robot's particle cloud.
test::Scatter cloud(const test::Scatter& all, std::size_t c, float half) {
  test::Scatter s;
  for (std::size_t p = 0; p < all.x.size(); ++p) {
    if (std::abs(all.x[p] - all.x[c]) <= half && std::abs(all.y[p] - all.y[c]) <= half) {
      s.x.push_back(all.x[p]);
      s.y.push_back(all.y[p]);
      s.theta.push_back(all.theta[p]);
    }
  }
  return s;
}

std::vector<float> cast(const RangeTable& table, const test::Scatter& s) {
  const RayBatch batch{s.x, s.y, s.theta, beams(), Pose2{0.05, 0.0, 0.0}, kMaxRange};
  std::vector<float> out(batch.ray_count());
  table.cast(batch, out);
  return out;
}

TEST(RangeTableTiles, ReadAsTheWholeTableThroughBuildsAndEvictions) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const RangeTable whole(grid, whole_options());
  const RangeTable tiled(grid, tiled_options());
  ASSERT_EQ(whole.stats().tile_cells, 0);
  ASSERT_EQ(tiled.stats().tile_cells, 64);
  ASSERT_EQ(tiled.stats().points, whole.stats().points);
  EXPECT_EQ(tiled.tiles_built(), 0U) << "nothing is built before the first cast";
  const test::Scatter all = test::scatter_in_free_cells(grid, 40000, 5);
  // Clouds 1.5 m across (at most 4 tiles each) at 16 places, then the first again: more
  // tiles than the budget holds, so later clouds evict earlier ones and the last rebuilds.
  std::vector<std::size_t> centres;
  for (std::size_t c = 0; c < 16; ++c) centres.push_back(c * 997);
  centres.push_back(centres.front());
  for (const std::size_t c : centres) {
    const test::Scatter s = cloud(all, c, 0.75F);
    ASSERT_GT(s.x.size(), 10U);
    EXPECT_EQ(cast(tiled, s), cast(whole, s)) << "cloud around pose " << c;
  }
  std::cout << "Intel tiled: " << tiled.stats().max_resident_tiles << " tiles resident at most, "
            << tiled.tiles_built() << " built for " << centres.size() << " clouds\n";
  EXPECT_GT(tiled.tiles_built(), tiled.stats().max_resident_tiles) << "no tile was evicted";
  // Single rays build their tiles too.
  for (std::size_t p = 0; p < all.x.size(); p += 4001) {
    const double angle = all.theta[p];
    EXPECT_EQ(tiled.cast_one({all.x[p], all.y[p]}, angle, kMaxRange),
              whole.cast_one({all.x[p], all.y[p]}, angle, kMaxRange));
  }
}

TEST(RangeTableTiles, SensorsInTilesTheBudgetCannotHoldAreCastExactly) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const RangeTable whole(grid, whole_options());
  const RangeTable tiled(grid, tiled_options());
  const RayCaster exact(grid);
  // Poses over the whole map need every tile, far more than the budget holds.
  const test::Scatter s = test::scatter_in_free_cells(grid, 3000, 8);
  const RayBatch batch{s.x, s.y, s.theta, beams(), Pose2{0.05, 0.0, 0.0}, kMaxRange};
  std::vector<float> from_exact(batch.ray_count());
  exact.cast(batch, from_exact);
  const std::vector<float> from_tiles = cast(tiled, s);
  const std::vector<float> from_whole = cast(whole, s);
  const std::size_t n = beams().size();
  std::size_t tabled = 0;
  std::size_t exactly = 0;
  for (std::size_t p = 0; p < s.x.size(); ++p) {
    bool as_table = true;
    bool as_exact = true;
    for (std::size_t b = 0; b < n; ++b) {
      as_table = as_table && from_tiles[p * n + b] == from_whole[p * n + b];
      as_exact = as_exact && from_tiles[p * n + b] == from_exact[p * n + b];
    }
    EXPECT_TRUE(as_table || as_exact) << "pose " << p << " reads neither table nor Embree";
    tabled += as_table && !as_exact ? 1 : 0;
    exactly += as_exact && !as_table ? 1 : 0;
  }
  EXPECT_GT(tabled, 0U);
  EXPECT_GT(exactly, s.x.size() / 2) << "most tiles cannot be held";
  EXPECT_LE(tiled.tiles_built(), tiled.stats().max_resident_tiles);
}

TEST(RangeTableTiles, SameOnAnyThreadCount) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const test::Scatter all = test::scatter_in_free_cells(grid, 20000, 6);
  std::vector<std::vector<float>> runs;
  for (const int threads : {1, 2}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      const RangeTable tiled(grid, tiled_options());
      std::vector<float> out;
      for (std::size_t c = 0; c < 12; ++c) {
        const std::vector<float> part = cast(tiled, cloud(all, c * 1499, 1.0F));
        out.insert(out.end(), part.begin(), part.end());
      }
      const std::vector<float> spread = cast(tiled, all);
      out.insert(out.end(), spread.begin(), spread.end());
      runs.push_back(out);
    });
  }
  EXPECT_EQ(runs[0], runs[1]);
}

}  // namespace
}  // namespace mote
