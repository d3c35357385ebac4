#include "mote/engine/recovery.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine_test_util.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/executor.hpp"

namespace mote {
namespace {

TEST(AugmentedMcl, MatchesTable83OnALikelihoodDrop) {
  AugmentedMcl mcl({0.01, 0.2});
  EXPECT_EQ(mcl.injection_probability(), 0.0);
  mcl.update(std::log(0.5));
  mcl.update(std::log(0.5));
  EXPECT_NEAR(mcl.injection_probability(), 0.0, 1e-12);  // steady likelihood: no injection
  mcl.update(std::log(0.05));
  const double slow = 0.99 * 0.5 + 0.01 * 0.05;
  const double fast = 0.8 * 0.5 + 0.2 * 0.05;
  EXPECT_NEAR(mcl.injection_probability(), 1.0 - fast / slow, 1e-12);
}

TEST(AugmentedMcl, SurvivesTinyAndDegenerateLikelihoods) {
  AugmentedMcl mcl;
  mcl.update(-5000.0);  // exp() underflows in double; the log domain does not
  mcl.update(-5000.0);
  EXPECT_NEAR(mcl.injection_probability(), 0.0, 1e-12);
  mcl.update(-std::numeric_limits<double>::infinity());  // every particle at weight 0
  const double p = mcl.injection_probability();
  EXPECT_NEAR(p, 1.0 - 0.9 / 0.999, 1e-9);
  AugmentedMcl off({0.0, 0.0});
  off.update(-1.0);
  off.update(-9.0);
  EXPECT_EQ(off.injection_probability(), 0.0);
}

test::CellFreeSpace two_cells() { return test::CellFreeSpace({{2.0, 3.0}, {-4.0, 0.0}}); }

TEST(InjectRandomParticles, ReplacesTheExpectedFractionInsideFreeSpace) {
  const test::CellFreeSpace space = two_cells();
  constexpr std::size_t kN = 40000;
  ParticleStore store(kN);
  const std::size_t replaced = inject_random_particles(store.view(), 0.25, space, 3, 7);
  // Binomial(N, 0.25): 5 standard deviations.
  EXPECT_NEAR(static_cast<double>(replaced), 0.25 * kN, 5.0 * std::sqrt(kN * 0.25 * 0.75));
  std::size_t moved = 0;
  for (std::size_t i = 0; i < kN; ++i) {
    const Pose2 p = store.view().pose(i);
    if (p == Pose2{}) continue;
    ++moved;
    ASSERT_TRUE(space.contains(p.x, p.y)) << p.x << " " << p.y;
  }
  EXPECT_EQ(moved, replaced);
  EXPECT_EQ(inject_random_particles(store.view(), 0.0, space, 3, 7), 0U);
}

TEST(InjectRandomParticles, IsIndependentOfThreadsAndGrain) {
  const test::CellFreeSpace space = two_cells();
  ParticleStore a(10000);
  ParticleStore b(10000);
  inject_random_particles(a.view(), 0.5, space, 1, 2, 1 << 20);
  const Executor ex(4);
  ex([&] { inject_random_particles(b.view(), 0.5, space, 1, 2, 16); });
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.view().pose(i), b.view().pose(i));
}

TEST(InitializeGaussian, HasTheRequestedMeanAndCovariance) {
  Eigen::Matrix3d cov;
  cov << 0.25, 0.1, 0.02, 0.1, 0.16, -0.01, 0.02, -0.01, 0.04;
  constexpr std::size_t kN = 200000;
  ParticleStore store;
  initialize_gaussian(store, kN, {3.0, -2.0, 3.0}, cov, 5);
  ASSERT_EQ(store.size(), kN);
  const ParticleView p = store.view();
  const Pose2 mean{3.0, -2.0, 3.0};
  const auto residual = [&](std::size_t i, int k) {
    return k == 0   ? p.x[i] - mean.x
           : k == 1 ? p.y[i] - mean.y
                    : wrap_angle(p.theta[i] - mean.theta);
  };
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const test::SampleStats s =
          test::sample_stats(kN, [&](std::size_t i) { return residual(i, r) * residual(i, c); });
      // Standard error of a sample covariance of Gaussians: sqrt((s_rr s_cc + s_rc^2) / N).
      const double se = std::sqrt((cov(r, r) * cov(c, c) + cov(r, c) * cov(r, c)) / kN);
      EXPECT_NEAR(s.mean, cov(r, c), 5.0 * se) << r << c;
    }
  }
  EXPECT_FLOAT_EQ(p.logw[0], -std::log(static_cast<float>(kN)));
}

TEST(InitializeGaussian, AcceptsZeroVarianceAndRejectsIndefinite) {
  ParticleStore store;
  initialize_gaussian(store, 100, {1.0, 2.0, 0.5}, Eigen::Vector3d(0.1, 0.1, 0.0).asDiagonal(), 1);
  for (std::size_t i = 0; i < store.size(); ++i) ASSERT_EQ(store.view().theta[i], 0.5F);
  Eigen::Matrix3d bad = Eigen::Matrix3d::Identity();
  bad(0, 0) = -1.0;
  EXPECT_THROW(initialize_gaussian(store, 100, {}, bad, 1), ConfigError);
}

TEST(InitializeUniform, FillsFreeSpaceOnly) {
  const test::CellFreeSpace space = two_cells();
  ParticleStore store;
  initialize_uniform(store, 5000, space, 9);
  std::size_t in_first = 0;
  for (std::size_t i = 0; i < store.size(); ++i) {
    const Pose2 p = store.view().pose(i);
    ASSERT_TRUE(space.contains(p.x, p.y));
    in_first += p.x > 0 ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(in_first), 2500.0, 5.0 * std::sqrt(5000 * 0.25));
  EXPECT_THROW(initialize_uniform(store, 10, test::CellFreeSpace({}), 1), ConfigError);
}

}  // namespace
}  // namespace mote
