#include "mote/engine/motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine_test_util.hpp"
#include "mote/engine/executor.hpp"

namespace mote {
namespace {

constexpr std::size_t kN = 200000;

ParticleStore store_at(const Pose2& p, std::size_t n = kN) {
  ParticleStore store(n);
  for (std::size_t i = 0; i < n; ++i) store.view().set_pose(i, p);
  return store;
}

// Thrun table 5.6 with alpha = 0.1, 0.05, 0.02, 0.02: the three noisy increments are
// independent normals, recovered exactly from each particle's displacement. alpha3 is small
// enough that trans_hat < 0 (which hypot/atan2 could not tell from a flipped rot1) is a
// 6.5-sigma event.
TEST(OdometryModel, IncrementsHaveTheAnalyticMeansAndVariances) {
  const OdometryModel model{0.1, 0.05, 0.02, 0.02, false};
  const Pose2 start{1.0, 2.0, 0.3};
  const Odometry u{{0.0, 0.0, 0.0}, {1.0, 0.5, 0.4}};
  const double trans = std::hypot(1.0, 0.5);
  const double rot1 = std::atan2(0.5, 1.0);
  const double rot2 = 0.4 - rot1;
  ParticleStore store = store_at(start);
  predict(model, u, store.view(), 11, 1);
  const ParticleView p = store.view();
  const auto rot1_hat = [&](std::size_t i) {
    return wrap_angle(std::atan2(p.y[i] - start.y, p.x[i] - start.x) - start.theta);
  };
  const auto trans_hat = [&](std::size_t i) {
    return std::hypot(p.x[i] - start.x, p.y[i] - start.y);
  };
  const auto rot2_hat = [&](std::size_t i) {
    return wrap_angle(p.theta[i] - start.theta - rot1_hat(i));
  };
  const struct {
    const char* name;
    test::SampleStats stats;
    double mean, variance;
  } cases[] = {
      {"rot1", test::sample_stats(kN, rot1_hat), rot1, 0.1 * rot1 * rot1 + 0.05 * trans * trans},
      {"trans", test::sample_stats(kN, trans_hat), trans,
       0.02 * trans * trans + 0.02 * (rot1 * rot1 + rot2 * rot2)},
      {"rot2", test::sample_stats(kN, rot2_hat), rot2, 0.1 * rot2 * rot2 + 0.05 * trans * trans},
  };
  for (const auto& c : cases) {
    // float storage of positions adds ~1e-7 error, far below the 5-sigma statistical band.
    EXPECT_NEAR(c.stats.mean, c.mean, c.stats.mean_tolerance()) << c.name;
    EXPECT_NEAR(c.stats.variance, c.variance, c.stats.variance_tolerance(c.variance)) << c.name;
  }
}

TEST(OdometryModel, AmclIgnoresHeadingOfTinyTranslations) {
  const OdometryModel model{0.0, 0.0, 0.0, 0.0, true};
  ParticleStore store = store_at({0.0, 0.0, 1.0}, 16);
  predict(model, {{0.0, 0.0, 0.0}, {0.0, 0.005, 0.2}}, store.view(), 1, 1);
  // rot1 = 0: the particle moves 5 mm along its own heading (1 rad), then turns by 0.2.
  EXPECT_NEAR(store.view().x[0], 0.005 * std::cos(1.0), 1e-6);
  EXPECT_NEAR(store.view().y[0], 0.005 * std::sin(1.0), 1e-6);
  EXPECT_NEAR(store.view().theta[0], 1.2, 1e-6);
}

TEST(OdometryModel, AmclTreatsBackwardMotionAsSmallRotation) {
  // Backwards by 1 m: rot1 = pi, rot2 = -pi. amcl's rotation noise is min(|rot|, |pi - rot|) = 0.
  const Odometry back{{0.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}};
  ParticleStore amcl = store_at({0.0, 0.0, 0.0}, 4096);
  ParticleStore thrun = store_at({0.0, 0.0, 0.0}, 4096);
  predict(OdometryModel{0.5, 0.0, 0.0, 0.0, true}, back, amcl.view(), 3, 1);
  predict(OdometryModel{0.5, 0.0, 0.0, 0.0, false}, back, thrun.view(), 3, 1);
  const auto spread = [](const ParticleView& p) {
    return test::sample_stats(p.size(), [&](std::size_t i) { return double{p.theta[i]}; }).variance;
  };
  EXPECT_LT(spread(amcl.view()), 1e-10);
  EXPECT_GT(spread(thrun.view()), 1.0);
  EXPECT_NEAR(amcl.view().x[7], -1.0, 1e-6);
}

// Pure forward translation of 1 m with heading 0: x = trans_hat, y = -strafe, theta = rot_hat.
TEST(OmniModel, StrafeAndTranslationNoiseMatchAmcl) {
  const OmniModel model{0.0, 0.03, 0.2, 0.0, 0.1};
  ParticleStore store = store_at({0.0, 0.0, 0.0});
  predict(model, {{2.0, 1.0, 0.0}, {3.0, 1.0, 0.0}}, store.view(), 5, 9);
  const ParticleView p = store.view();
  const test::SampleStats x = test::sample_stats(kN, [&](std::size_t i) { return double{p.x[i]}; });
  const test::SampleStats y = test::sample_stats(kN, [&](std::size_t i) { return double{p.y[i]}; });
  const test::SampleStats t =
      test::sample_stats(kN, [&](std::size_t i) { return double{p.theta[i]}; });
  EXPECT_NEAR(x.mean, 1.0, x.mean_tolerance());
  EXPECT_NEAR(x.variance, 0.2, x.variance_tolerance(0.2));
  EXPECT_NEAR(y.mean, 0.0, y.mean_tolerance());
  EXPECT_NEAR(y.variance, 0.1, y.variance_tolerance(0.1));
  EXPECT_NEAR(t.variance, 0.03, t.variance_tolerance(0.03));
}

TEST(AckermannModel, WithoutNoiseFollowsTheOdometryArcExactly) {
  AckermannModel model;
  model.alpha_distance = model.alpha_steering = model.steering_floor = 0.0;
  const double radius = 2.0;
  const double a = 0.3;  // steering = atan(0.33 / 2) is within max_steering
  const Odometry u{
      {5.0, -1.0, 0.7},
      compose({5.0, -1.0, 0.7}, {radius * std::sin(a), radius * (1 - std::cos(a)), a})};
  const Pose2 start{1.0, 1.0, 0.5};
  ParticleStore store = store_at(start, 16);
  predict(model, u, store.view(), 1, 1);
  const Pose2 expected = compose(start, between(u.previous, u.current));
  EXPECT_NEAR(store.view().x[3], expected.x, 1e-5);
  EXPECT_NEAR(store.view().y[3], expected.y, 1e-5);
  EXPECT_NEAR(store.view().theta[3], expected.theta, 1e-5);
}

TEST(AckermannModel, ReversesAndSpreadsAlongTheArc) {
  AckermannModel model;
  ParticleStore store = store_at({0.0, 0.0, 0.0}, 4096);
  predict(model, {{0.0, 0.0, 0.0}, {-0.5, 0.0, 0.0}}, store.view(), 2, 1);
  const ParticleView p = store.view();
  const test::SampleStats x =
      test::sample_stats(p.size(), [&](std::size_t i) { return double{p.x[i]}; });
  const double sd_s = std::sqrt(model.alpha_distance) * 0.5;
  EXPECT_NEAR(x.mean, -0.5, x.mean_tolerance() + 1e-3);
  EXPECT_NEAR(x.variance, sd_s * sd_s, x.variance_tolerance(sd_s * sd_s) + 1e-5);
}

// A user model through the concept: a fixed shift, so the test knows every result.
struct Shift {
  float dx = 0.0F;
  void sample(const Odometry&, const ParticleView& p, std::size_t begin, std::size_t end,
              const RngStream&) const {
    for (std::size_t i = begin; i < end; ++i) p.x[i] += dx;
  }
};
static_assert(MotionModel<Shift>);

TEST(Predict, RunsUserModelsOverEveryParticleInParallel) {
  ParticleStore store = store_at({1.0, 0.0, 0.0}, 10000);
  const Executor ex(2);
  ex([&] { predict(Shift{0.5F}, {}, store.view(), 1, 1, 64); });
  for (std::size_t i = 0; i < store.size(); ++i) ASSERT_EQ(store.view().x[i], 1.5F) << i;
}

TEST(Predict, GivesTheSameBitsForAnyThreadCountAndGrain) {
  const OdometryModel model;
  const Odometry u{{0.0, 0.0, 0.0}, {0.3, -0.1, 0.2}};
  ParticleStore reference = store_at({1.0, 2.0, 3.0}, 10001);
  Executor(1)([&] { predict(model, u, reference.view(), 9, 4, 1 << 20); });
  for (const int threads : {2, 4}) {
    for (const std::size_t grain : {std::size_t{16}, std::size_t{1000}}) {
      ParticleStore other = store_at({1.0, 2.0, 3.0}, 10001);
      const Executor ex(threads);
      ex([&] { predict(model, u, other.view(), 9, 4, grain); });
      for (std::size_t i = 0; i < reference.size(); ++i) {
        ASSERT_EQ(other.view().x[i], reference.view().x[i]) << threads << " " << grain;
        ASSERT_EQ(other.view().theta[i], reference.view().theta[i]);
      }
    }
  }
}

}  // namespace
}  // namespace mote
