// The batched API: per-ray equality with cast_one, thread-count independence, packets versus
// single rays, and the contract on bad input.

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "grids.hpp"
#include "mote/core/error.hpp"
#include "mote/raycast/grid_ray_caster.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote {
namespace {

/// A 60 x 40 grid of 0.1 m cells with random walls (20 %) and unknown cells (5 %), yawed.
OccupancyGrid cluttered_grid() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<> u(0.0, 1.0);
  std::vector<std::string> rows(40, std::string(60, '.'));
  for (auto& row : rows) {
    for (char& c : row) {
      const double x = u(rng);
      c = x < 0.2 ? '#' : x < 0.25 ? '?' : '.';
    }
  }
  return test::grid_from_rows(rows, 0.1, {1.0, -2.0, 0.3});
}

/// Particles spread over and around the grid, with 24 beams over 270 degrees.
struct Particles {
  std::vector<float> x, y, theta, beams;
  explicit Particles(std::size_t n) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> px(-1.0F, 8.0F), py(-3.0F, 4.0F), pt(-3.1F, 3.1F);
    for (std::size_t i = 0; i < n; ++i) {
      x.push_back(px(rng));
      y.push_back(py(rng));
      theta.push_back(pt(rng));
    }
    for (int b = 0; b < 24; ++b) beams.push_back(-2.35F + 0.2F * static_cast<float>(b));
  }
  RayBatch batch(float max_range) const {
    return {x, y, theta, beams, Pose2{0.2, -0.05, 0.1}, max_range};
  }
};

template <class Caster>
class BatchCast : public ::testing::Test {};
using Casters = ::testing::Types<RayCaster, GridRayCaster>;
TYPED_TEST_SUITE(BatchCast, Casters);

TYPED_TEST(BatchCast, EqualsCastOnePerRay) {
  const TypeParam caster(cluttered_grid());
  const Particles p(300);
  const RayBatch batch = p.batch(6.0F);
  std::vector<float> ranges(batch.ray_count());
  caster.cast(batch, ranges);
  int hits = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    const Pose2 sensor = compose({p.x[i], p.y[i], p.theta[i]}, batch.sensor_offset);
    for (std::size_t b = 0; b < p.beams.size(); ++b) {
      const float one = caster.cast_one({sensor.x, sensor.y}, sensor.theta + p.beams[b], 6.0F);
      const float got = ranges[i * p.beams.size() + b];
      hits += got < 6.0F ? 1 : 0;
      // The two paths build the same ray with different rounding (rotation of precomputed beam
      // directions versus cos/sin of the summed angle), so they agree to float precision.
      EXPECT_NEAR(got, one, 1e-4F) << "particle " << i << " beam " << b;
    }
  }
  EXPECT_GT(hits, static_cast<int>(batch.ray_count()) / 2);
}

TYPED_TEST(BatchCast, IdenticalForOneAndTwoThreads) {
  RayCastOptions options;
  options.particle_grain = 16;
  const TypeParam caster(cluttered_grid(), options);
  const Particles p(2000);
  const RayBatch batch = p.batch(6.0F);
  std::vector<float> one(batch.ray_count()), two(batch.ray_count());
  tbb::task_arena(1).execute([&] { caster.cast(batch, one); });
  tbb::task_arena(2).execute([&] { caster.cast(batch, two); });
  EXPECT_EQ(one, two);
}

TYPED_TEST(BatchCast, SensorInsideWallReadsZeroOnEveryBeam) {
  const TypeParam caster(test::box_room());
  const std::vector<float> x{0.25F, 2.5F}, y{0.25F, 2.5F}, theta{0.0F, 0.0F}, beams{0.0F, 1.0F};
  std::vector<float> ranges(4);
  caster.cast({x, y, theta, beams, {}, 10.0F}, ranges);
  EXPECT_EQ(ranges[0], 0.0F);
  EXPECT_EQ(ranges[1], 0.0F);
  EXPECT_NEAR(ranges[2], 2.0F, 1e-5F);
}

TYPED_TEST(BatchCast, NonFinitePoseGivesNaN) {
  const TypeParam caster(test::box_room());
  const std::vector<float> x{NAN, 2.5F}, y{1.0F, 2.5F}, theta{0.0F, 0.0F}, beams{0.0F};
  std::vector<float> ranges(2);
  caster.cast({x, y, theta, beams, {}, 10.0F}, ranges);
  EXPECT_TRUE(std::isnan(ranges[0]));
  EXPECT_NEAR(ranges[1], 2.0F, 1e-5F);
}

TYPED_TEST(BatchCast, RejectsMismatchedInput) {
  const TypeParam caster(test::box_room());
  const std::vector<float> two{1.0F, 1.0F}, one{1.0F}, beams{0.0F, 0.5F};
  std::vector<float> ranges(4), short_ranges(3);
  EXPECT_THROW(caster.cast({two, one, two, beams, {}, 5.0F}, ranges), ConfigError);
  EXPECT_THROW(caster.cast({two, two, two, beams, {}, 5.0F}, short_ranges), ConfigError);
  EXPECT_THROW(caster.cast({two, two, two, beams, {}, 0.0F}, ranges), ConfigError);
  EXPECT_THROW(caster.cast({two, two, two, beams, {}, INFINITY}, ranges), ConfigError);
  EXPECT_THROW((void)caster.cast_one({1.0, 1.0}, 0.0, -1.0F), ConfigError);
}

TEST(EmbreeRayCaster, PacketsAndSingleRaysGiveTheSameRanges) {
  RayCastOptions single;
  single.packets = false;
  const auto grid = cluttered_grid();
  const Particles p(500);
  const RayBatch batch = p.batch(6.0F);
  std::vector<float> packets(batch.ray_count()), singles(batch.ray_count());
  RayCaster(grid).cast(batch, packets);
  RayCaster(grid, single).cast(batch, singles);
  EXPECT_EQ(packets, singles);
}

TEST(EmbreeRayCaster, MergesWallEdgesIntoMaximalSegments) {
  // The box room's ring has an outer and an inner boundary, four straight sides each.
  EXPECT_EQ(RayCaster(test::box_room()).wall_count(), 8U);
}

TEST(EmbreeRayCaster, EmptyMapHitsNothing) {
  const auto grid = test::grid_from_rows({"...", "..."}, 1.0);
  EXPECT_EQ(RayCaster(grid).cast_one({-1.0, 0.5}, 0.0, 7.0F), 7.0F);
  EXPECT_EQ(RayCaster(grid).wall_count(), 0U);
}

}  // namespace
}  // namespace mote
