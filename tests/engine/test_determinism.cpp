// The determinism contract (design.md section 3): 50 full updates (motion, a Gaussian
// log-likelihood around a moving true pose, normalize, KLD count, systematic resampling,
// recovery injection) give bit-identical particle sets for 1, 2 and 4 threads and two grains.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "engine_test_util.hpp"
#include "mote/engine/estimate.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/motion.hpp"
#include "mote/engine/recovery.hpp"
#include "mote/engine/resample.hpp"
#include "mote/engine/weights.hpp"

namespace mote {
namespace {

struct RunResult {
  std::vector<float> columns;  // x, y, theta, logw of the final set, back to back
  Pose2 estimate;
  Pose2 truth;
};

// The robot drives a circle; odometry is the true motion with a drift.
Pose2 true_pose(int step) {
  const double a = 0.05 * step;
  return {3.0 * std::sin(a), 3.0 * (1 - std::cos(a)), wrap_angle(a)};
}

RunResult run_filter(int threads, std::size_t grain) {
  constexpr std::uint64_t kSeed = 2024;
  const Executor ex(threads);
  const test::CellFreeSpace space({{-1.0, -1.0}, {0.0, 0.0}, {1.0, 1.0}});
  ParticleStore store;
  KldBins bins({-10.0, -10.0, 10.0, 10.0}, 0.5, 0.5, 10.0 * std::numbers::pi / 180);
  KldConfig kld;
  kld.min_particles = 300;
  kld.max_particles = 6000;
  AugmentedMcl recovery({0.01, 0.3});
  const OdometryModel motion{0.05, 0.05, 0.05, 0.05, true};
  RunResult out;
  ex([&] {
    initialize_gaussian(store, 5003, true_pose(0), Eigen::Vector3d(0.1, 0.1, 0.05).asDiagonal(),
                        kSeed, grain);
    for (int step = 1; step <= 50; ++step) {
      const Pose2 truth = true_pose(step);
      const Odometry u{compose({1.0, 0.0, 0.0}, true_pose(step - 1)),
                       compose({1.0, 0.0, 0.0}, truth)};
      predict(motion, u, store.view(), kSeed, static_cast<std::uint64_t>(step), grain);
      reweight(
          store.view(),
          [&](float x, float y, float theta) {
            const double dx = x - truth.x, dy = y - truth.y;
            const double dt = wrap_angle(theta - truth.theta);
            return -0.5 * (dx * dx + dy * dy) / 0.04 - 0.5 * dt * dt / 0.01;
          },
          1.0, grain);
      const NormalizeResult r = normalize(store.view(), grain);
      recovery.update(r.log_mean_likelihood);
      const std::size_t n = kld_sample_count(store.view(), bins, kld, grain);
      resample_systematic(store, n, kSeed, static_cast<std::uint64_t>(step), grain);
      inject_random_particles(store.view(), recovery.injection_probability(), space, kSeed,
                              static_cast<std::uint64_t>(step), grain);
    }
    out.estimate = estimate(store.view()).mean;
  });
  const ConstParticleView v = store.view();
  for (const float* c : {v.x, v.y, v.theta, v.logw})
    out.columns.insert(out.columns.end(), c, c + v.size());
  out.truth = true_pose(50);
  return out;
}

TEST(Determinism, FiftyUpdatesAreBitIdenticalAcrossThreadsAndGrains) {
  const RunResult reference = run_filter(1, 64);
  // The filter works: it tracks the true pose it was weighted around.
  EXPECT_NEAR(reference.estimate.x, reference.truth.x, 0.1);
  EXPECT_NEAR(reference.estimate.y, reference.truth.y, 0.1);
  EXPECT_NEAR(wrap_angle(reference.estimate.theta - reference.truth.theta), 0.0, 0.05);
  for (const std::size_t grain : {64UL, 4096UL}) {
    for (const int threads : {1, 2, 4}) {
      const RunResult other = run_filter(threads, grain);
      ASSERT_EQ(other.columns.size(), reference.columns.size()) << threads << " threads";
      EXPECT_EQ(std::memcmp(other.columns.data(), reference.columns.data(),
                            reference.columns.size() * sizeof(float)),
                0)
          << threads << " threads, grain " << grain;
      EXPECT_EQ(other.estimate, reference.estimate);
    }
  }
}

}  // namespace
}  // namespace mote
