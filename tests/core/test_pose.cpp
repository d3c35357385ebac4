#include "mote/core/pose.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace mote {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WrapAngle, MapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(3 * kPi), kPi);
  EXPECT_NEAR(wrap_angle(2 * kPi + 0.25), 0.25, 1e-12);
  EXPECT_NEAR(wrap_angle(-2 * kPi - 0.25), -0.25, 1e-12);
  for (double a = -20.0; a < 20.0; a += 0.37) {
    const double w = wrap_angle(a);
    EXPECT_GT(w, -kPi);
    EXPECT_LE(w, kPi);
    EXPECT_NEAR(std::remainder(w - a, 2 * kPi), 0.0, 1e-12);
  }
}

TEST(Pose2, ComposeWithInverseIsIdentity) {
  const Pose2 a{1.5, -2.0, 2.9};
  const Pose2 id = compose(inverse(a), a);
  EXPECT_NEAR(id.x, 0.0, 1e-12);
  EXPECT_NEAR(id.y, 0.0, 1e-12);
  EXPECT_NEAR(id.theta, 0.0, 1e-12);
}

TEST(Pose2, ComposeRotatesTheSecondPose) {
  const Pose2 c = compose({1.0, 2.0, kPi / 2}, {1.0, 0.0, kPi / 2});
  EXPECT_NEAR(c.x, 1.0, 1e-12);
  EXPECT_NEAR(c.y, 3.0, 1e-12);
  EXPECT_NEAR(c.theta, kPi, 1e-12);
}

TEST(Pose2, BetweenRecoversTheRelativeMotion) {
  const Pose2 a{0.3, 0.4, -3.0};
  const Pose2 b{-1.0, 2.0, 3.0};
  const Pose2 back = compose(a, between(a, b));
  EXPECT_NEAR(back.x, b.x, 1e-12);
  EXPECT_NEAR(back.y, b.y, 1e-12);
  EXPECT_NEAR(back.theta, b.theta, 1e-12);
}

TEST(Pose2, IsFiniteRejectsNaN) {
  EXPECT_TRUE(is_finite(Pose2{1, 2, 3}));
  EXPECT_FALSE(is_finite(Pose2{std::numeric_limits<double>::quiet_NaN(), 0, 0}));
  EXPECT_FALSE(is_finite(Pose2{0, 0, std::numeric_limits<double>::infinity()}));
}

}  // namespace
}  // namespace mote
