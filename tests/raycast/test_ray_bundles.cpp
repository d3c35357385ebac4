// Rays cast in bundles (raycast/src/ray_bundles.hpp) on the recorded maps: the exact grid
// walk's ranges for tracking clouds and for scattered sensors, whatever group or grouping a
// sensor falls in; and the Embree caster, which casts all of a gathered set's rays so, reads the
// grid walk's ranges there, the same whole or in prepared parts, on 1 or 2 threads.

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <cstddef>
#include <numbers>
#include <random>
#include <vector>

#include "grid_walk.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/grid_ray_caster.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote_test/data.hpp"
#include "ray_bundles.hpp"
#include "ray_setup.hpp"

namespace mote {
namespace {

constexpr float kMaxRange = 30.0F;
constexpr int kBeams = 60;

struct Poses {
  std::vector<float> x, y, theta;
};

/// `clouds` robots' particle clouds (`per_cloud` poses, sigma `spread` m and `turn` rad around
/// a free pose each), as a tracking filter holds them.
Poses clouds(const OccupancyGrid& grid, int clouds, int per_cloud, double spread, double turn,
             unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<> u(0.0, 1.0);
  std::normal_distribution<> n(0.0, 1.0);
  const auto& free = grid.free_cells();
  Poses p;
  for (int c = 0; c < clouds; ++c) {
    const Point2 centre = grid.free_point(
        static_cast<std::size_t>(u(rng) * static_cast<double>(free.size())) % free.size(), 0.5,
        0.5);
    const double heading = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    for (int k = 0; k < per_cloud; ++k) {
      p.x.push_back(static_cast<float>(centre.x + spread * n(rng)));
      p.y.push_back(static_cast<float>(centre.y + spread * n(rng)));
      p.theta.push_back(static_cast<float>(heading + turn * n(rng)));
    }
  }
  return p;
}

std::vector<float> beam_angles() {
  std::vector<float> b;
  for (int k = 0; k < kBeams; ++k) {
    b.push_back(static_cast<float>(-std::numbers::pi + 2.0 * std::numbers::pi * k / kBeams));
  }
  return b;
}

RayBatch batch_of(const Poses& p, const std::vector<float>& beams) {
  return {p.x, p.y, p.theta, beams, Pose2{0.1, 0.0, 0.0}, kMaxRange};
}

/// The map's blocking mask and frame, as the casters hold them.
struct MapView {
  explicit MapView(const OccupancyGrid& grid)
      : blocking(detail::blocking_mask(grid, true)),
        mask{grid.width(), grid.height(), static_cast<float>(grid.resolution()), blocking.data()},
        frame(grid.origin()),
        bits(mask) {}
  std::vector<std::uint8_t> blocking;
  detail::CellMask mask;
  detail::GridFrame frame;
  detail::BitMask bits;
};

/// Every group of the batch cast in bundles; rays of sensors in no group keep `fill`.
std::vector<float> cast_in_bundles(const MapView& v, const RayBatch& batch, float fill,
                                   detail::BundleGrouping grouping = {}) {
  std::vector<float> ranges(batch.ray_count(), fill);
  const detail::BatchRays rays(v.frame, v.mask, batch, ranges.size());
  const detail::BundleGroups groups = detail::group_for_bundles(rays, v.mask, 64, 1, grouping);
  detail::BundleScratch scratch;
  for (std::size_t g = 0; g < groups.count(); ++g) {
    detail::cast_bundle_group(rays, v.mask, v.bits, groups, g, ranges, scratch, {0, rays.beams()});
  }
  return ranges;
}

void expect_grid_walk_ranges(const std::filesystem::path& yaml, double spread, double turn,
                             detail::BundleGrouping grouping = {}) {
  const OccupancyGrid grid = load_map(yaml);
  const MapView v(grid);
  const std::vector<float> beams = beam_angles();
  const Poses poses = clouds(grid, 12, 200, spread, turn, 7);
  const RayBatch batch = batch_of(poses, beams);
  const std::vector<float> got = cast_in_bundles(v, batch, -1.0F, grouping);
  const detail::BatchRays rays(v.frame, v.mask, batch, got.size());
  const double diagonal = grid.resolution() * std::numbers::sqrt2;
  int cast = 0;
  int hits = 0;
  int off_1mm = 0;
  int off_diagonal = 0;
  for (std::size_t p = 0; p < rays.particles(); ++p) {
    const detail::SensorFrame s = rays.sensor(p);
    for (std::size_t b = 0; b < rays.beams(); ++b) {
      const float r = got[p * rays.beams() + b];
      if (r == -1.0F) continue;  // in a wall or off the map: not the bundles' rays
      const float walk = detail::walk_grid(v.mask, rays.ray(s, b), kMaxRange);
      ++cast;
      hits += walk < kMaxRange ? 1 : 0;
      off_1mm += std::abs(r - walk) > 1e-3F ? 1 : 0;
      if (std::abs(r - walk) > diagonal && ++off_diagonal <= 5) {
        ADD_FAILURE() << yaml.filename() << " sensor " << p << " pose " << poses.x[p] << " "
                      << poses.y[p] << " " << poses.theta[p] << " beam " << b << ": bundles " << r
                      << " m, grid walk " << walk << " m";
      }
    }
  }
  // Most sensors are in free space: a test of nothing cast would prove nothing.
  EXPECT_GT(cast, static_cast<int>(batch.ray_count() / 2));
  EXPECT_GT(hits, cast / 2);
  EXPECT_EQ(off_diagonal, 0) << "of " << cast << " rays";
  // Float cells against the walk's doubles: a ray grazing a wall may differ by a hair more.
  EXPECT_LE(off_1mm, cast / 10000) << "of " << cast << " rays";
}

TEST(RayBundles, GridWalkRangesForTrackingCloudsOnIntel) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  expect_grid_walk_ranges(path, 0.1, 0.05);
}

TEST(RayBundles, GridWalkRangesForTrackingCloudsOnWillow) {
  MOTE_REQUIRE_DATA(path, "maps/willow-full-0.05.yaml");
  expect_grid_walk_ranges(path, 0.1, 0.05);
}

TEST(RayBundles, GridWalkRangesForScatteredSensorsOnIntel) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  expect_grid_walk_ranges(path, 3.0, 3.0);  // groups of one or two
}

TEST(RayBundles, GridWalkRangesInTwoDegreeBinsAndBlocksOf32OnIntel) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  expect_grid_walk_ranges(path, 0.4, 0.16, {180, 32});  // wide wedges, full bundles
}

TEST(RayBundles, ARangeDoesNotDependOnTheGroupingItWasCastIn) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const MapView v(grid);
  const std::vector<float> beams = beam_angles();
  const Poses poses = clouds(grid, 4, 300, 0.2, 0.08, 13);  // the batch's spans view these
  const RayBatch batch = batch_of(poses, beams);
  const std::vector<float> finest = cast_in_bundles(v, batch, -1.0F);
  for (const detail::BundleGrouping g : {detail::BundleGrouping{720, 32}, {360, 32}, {180, 32}}) {
    EXPECT_EQ(cast_in_bundles(v, batch, -1.0F, g), finest)
        << g.heading_bins << " bins, blocks of " << g.block_cells;
  }
}

TEST(RayBundles, ARangeDoesNotDependOnTheGroupItWasCastIn) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const MapView v(grid);
  const std::vector<float> beams = beam_angles();
  const Poses poses = clouds(grid, 3, 150, 0.1, 0.05, 11);
  const std::vector<float> together = cast_in_bundles(v, batch_of(poses, beams), -1.0F);
  for (std::size_t p = 0; p < poses.x.size(); p += 7) {
    const Poses one{{poses.x[p]}, {poses.y[p]}, {poses.theta[p]}};
    const std::vector<float> alone = cast_in_bundles(v, batch_of(one, beams), -1.0F);
    for (std::size_t b = 0; b < beams.size(); ++b) {
      ASSERT_EQ(alone[b], together[p * beams.size() + b]) << "sensor " << p << " beam " << b;
    }
  }
}

TEST(RayBundles, OnlyTheRaysLeftToCastAreCast) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const MapView v(grid);
  const std::vector<float> beams = beam_angles();
  const Poses poses = clouds(grid, 1, 100, 0.1, 0.05, 5);
  const RayBatch batch = batch_of(poses, beams);
  const std::vector<float> all = cast_in_bundles(v, batch, -1.0F);
  // Every third ray marked as left to cast, the others holding a value the cast must keep.
  std::vector<float> some(all.size());
  for (std::size_t k = 0; k < some.size(); ++k) some[k] = k % 3 == 0 ? -1.0F : 123.0F;
  const detail::BatchRays rays(v.frame, v.mask, batch, some.size());
  const detail::BundleGroups groups = detail::group_for_bundles(rays, v.mask, 64, 1);
  detail::BundleScratch scratch;
  for (std::size_t g = 0; g < groups.count(); ++g) {
    detail::cast_bundle_group(rays, v.mask, v.bits, groups, g, some, scratch, {0, rays.beams()},
                              -1.0F);
  }
  for (std::size_t k = 0; k < some.size(); ++k) {
    ASSERT_EQ(some[k], k % 3 == 0 ? all[k] : 123.0F) << "ray " << k;
  }
}

/// A caster's ranges prepared on the whole set and cast in two parts, in an arena of `threads`.
template <class Caster>
std::vector<float> prepared_in_two_parts(const Caster& caster, const Poses& poses,
                                         const std::vector<float>& beams, int threads) {
  std::vector<float> parts(poses.x.size() * beams.size());
  tbb::task_arena arena(threads);
  arena.execute([&] {
    caster.prepare(batch_of(poses, beams));
    const std::size_t half = poses.x.size() / 2;
    const auto part = [&](std::size_t begin, std::size_t end) {
      const Poses some{
          {poses.x.begin() + std::ptrdiff_t(begin), poses.x.begin() + std::ptrdiff_t(end)},
          {poses.y.begin() + std::ptrdiff_t(begin), poses.y.begin() + std::ptrdiff_t(end)},
          {poses.theta.begin() + std::ptrdiff_t(begin), poses.theta.begin() + std::ptrdiff_t(end)}};
      caster.cast_prepared(
          batch_of(some, beams),
          std::span(parts).subspan(begin * beams.size(), (end - begin) * beams.size()));
    };
    part(0, half);
    part(half, poses.x.size());
  });
  return parts;
}

TEST(RayCasterPrepared, GatheredSensorsReadTheGridWalksRangesFromBundles) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const RayCaster caster(grid);
  const std::vector<float> beams = beam_angles();
  const Poses poses = clouds(grid, 1, 3000, 0.05, 0.01, 5);
  const RayBatch batch = batch_of(poses, beams);
  std::vector<float> embree(batch.ray_count());
  caster.cast(batch, embree);
  std::vector<float> got(batch.ray_count());
  caster.prepare(batch);
  caster.cast_prepared(batch, got);
  const GridRayCaster walk(grid);
  std::vector<float> walked(batch.ray_count());
  walk.cast(batch, walked);
  const auto diagonal = static_cast<float>(std::numbers::sqrt2 * grid.resolution());
  int differ = 0;
  int off_walk = 0;
  int off_embree = 0;
  for (std::size_t k = 0; k < got.size(); ++k) {
    differ += got[k] != embree[k] ? 1 : 0;
    off_walk += std::abs(got[k] - walked[k]) > 1e-3F ? 1 : 0;
    off_embree += std::abs(got[k] - embree[k]) > diagonal ? 1 : 0;
  }
  // Cast in bundles (arithmetic other than Embree's in the last bits), the grid walk's ranges,
  // and Embree's within a cell diagonal but at ties at a wall's reach (one in 10 000 at most).
  EXPECT_GT(differ, 0) << "no ray was cast in bundles";
  EXPECT_LE(off_walk, static_cast<int>(got.size() / 10000));
  EXPECT_LE(off_embree, static_cast<int>(got.size() / 10000));
  for (const int threads : {1, 2}) {
    EXPECT_EQ(prepared_in_two_parts(caster, poses, beams, threads), got) << threads << " threads";
  }
}

TEST(RayCasterPrepared, ScatteredSensorsStayOnEmbree) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const RayCaster caster(grid);
  const std::vector<float> beams = beam_angles();
  // A global localization's particles: no group comes near the size where bundles pay.
  const Poses poses = clouds(grid, 300, 10, 1.0, 3.0, 6);
  const RayBatch batch = batch_of(poses, beams);
  std::vector<float> embree(batch.ray_count());
  caster.cast(batch, embree);
  EXPECT_EQ(prepared_in_two_parts(caster, poses, beams, 2), embree);
}

TEST(RayCasterPrepared, ASetThatGathersOnlyAsAWholeStaysOnEmbree) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const RayCaster caster(grid);
  const MapView v(grid);
  const std::vector<float> beams = beam_angles();
  // Sensors all over the map with one heading, in no spatial order, as a global set's after its
  // first updates: they gather as a whole, but every part of 4096 holds a few a group.
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<> u(0.0, 1.0);
  const auto& free = grid.free_cells();
  Poses poses;
  for (int k = 0; k < 40000; ++k) {
    const Point2 p = grid.free_point(
        static_cast<std::size_t>(u(rng) * static_cast<double>(free.size())) % free.size(), u(rng),
        u(rng));
    poses.x.push_back(static_cast<float>(p.x));
    poses.y.push_back(static_cast<float>(p.y));
    poses.theta.push_back(static_cast<float>(0.3 + 0.004 * u(rng)));
  }
  const RayBatch batch = batch_of(poses, beams);
  const detail::BatchRays rays(v.frame, v.mask, batch, batch.ray_count());
  ASSERT_GE(detail::group_for_bundles(rays, v.mask, 64, 1).mean_size(),
            detail::kBundlesPayForEveryRay);
  EXPECT_LT(detail::part_group_size(rays, v.mask, detail::kPreparedPart),
            detail::kBundlesPayForEveryRay);
  std::vector<float> embree(batch.ray_count());
  caster.cast(batch, embree);
  std::vector<float> got(batch.ray_count());
  caster.prepare(batch);
  caster.cast_prepared(batch, got);
  EXPECT_EQ(got, embree);
}

}  // namespace
}  // namespace mote
