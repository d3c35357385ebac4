// The Ackermann model's noise fit on draws from the model itself: odometry arcs, true arcs drawn
// around them as AckermannModel draws them, both turned into increments by the bicycle's
// forward kinematics. (The simulator drives a differential robot that turns on the spot, so it
// cannot be this fit's oracle.)
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/motion.hpp"

namespace mote::calibrate {
namespace {

constexpr double kWheelbase = 0.33;

/// The increment of an arc of length s at steering angle phi (AckermannModel::sample's
/// kinematics in double): dtheta = s tan(phi) / L along the mid-arc heading.
Pose2 arc_increment(double s, double phi) {
  const double dtheta = s * std::tan(phi) / kWheelbase;
  const double half = 0.5 * dtheta;
  const double chord = std::abs(half) < 1e-9 ? s : s * std::sin(half) / half;
  return {chord * std::cos(half), chord * std::sin(half), dtheta};
}

struct Noise {
  double distance, steering;  // alpha3, alpha1
  // Std of the independent errors of both poses in the map frame (m, m, rad): different in x
  // and y, so that only a covariance turned into the motion's direction accounts for them.
  double pose_x = 0, pose_y = 0, pose_theta = 0;
  double max_phi = 0.3;  // rad, the odometry arcs' steering: up to this
};

/// n increments: odometry arcs of 5-50 cm (one in ten reversing) at up to max_phi of steering,
/// the motion's arcs drawn around them, from poses at random headings, and the poses' errors
/// (with their covariance) on top.
std::vector<MotionSample> draws(const Noise& noise, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  const double floor = AckermannModel{}.steering_floor;
  const PoseCovariance cov{noise.pose_x * noise.pose_x, 0.0, noise.pose_y * noise.pose_y,
                           noise.pose_theta * noise.pose_theta};
  const auto perturbed = [&](const Pose2& p) {
    return Pose2{p.x + noise.pose_x * g(rng), p.y + noise.pose_y * g(rng),
                 p.theta + noise.pose_theta * g(rng)};
  };
  std::vector<MotionSample> out;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = (u(rng) < 0.1 ? -1.0 : 1.0) * (0.05 + 0.45 * u(rng));
    const double phi = noise.max_phi * (2.0 * u(rng) - 1.0);
    const double true_s = s + std::sqrt(noise.distance) * std::abs(s) * g(rng);
    const double true_phi = phi + std::sqrt(noise.steering * phi * phi + floor) * g(rng);
    const Pose2 start{10.0 * u(rng), 10.0 * u(rng), 6.0 * u(rng) - 3.0};
    const Pose2 before = perturbed(start);
    const Pose2 after = perturbed(compose(start, arc_increment(true_s, true_phi)));
    MotionSample m;
    m.odometry = arc_increment(s, phi);
    m.motion = between(before, after);
    m.heading_before = before.theta;
    m.before = m.after = cov;
    out.push_back(m);
  }
  return out;
}

void expect_recovered(const Noise& noise, bool estimated, std::size_t min_used = 1400) {
  const AckermannFit fit = fit_ackermann_noise(draws(noise, 1500, 5), kWheelbase, estimated);
  // Issue 17's bound for every alpha: 15 % (the standard error of a variance from 1500 draws
  // is about 4 %).
  EXPECT_NEAR(fit.alpha_distance, noise.distance, 0.15 * noise.distance);
  EXPECT_NEAR(fit.alpha_steering, noise.steering, 0.15 * noise.steering);
  EXPECT_GT(fit.quality.samples, min_used);
  EXPECT_GT(fit.quality.log_likelihood_after, fit.quality.log_likelihood_before);
}

TEST(CalibrateAckermann, RecoversSteeringAndDistanceNoise) {
  expect_recovered({.distance = 0.02, .steering = 0.1}, false);
  expect_recovered({.distance = 0.1, .steering = 0.02}, false);
}

/// Between noisy poses (1.5 cm across x, 0.5 cm across y, 6 mrad) whose covariance comes with
/// them, as the refined trajectory hands them over: the poses' noise is not taken for odometry
/// noise, whether the fit trusts the covariances alone (a reference) or also fits a floor
/// (estimated poses).
TEST(CalibrateAckermann, RecoversNoiseBetweenNoisyPoses) {
  const Noise noise{
      .distance = 0.02, .steering = 0.1, .pose_x = 0.015, .pose_y = 0.005, .pose_theta = 0.006};
  expect_recovered(noise, false);
  expect_recovered(noise, true);
  // The poses' noise matters in these draws: ignored, it inflates both noises.
  std::vector<MotionSample> blind = draws(noise, 1500, 5);
  for (MotionSample& m : blind) m.before = m.after = {};
  const AckermannFit fit = fit_ackermann_noise(blind, kWheelbase, false);
  EXPECT_GT(fit.alpha_steering, 1.15 * noise.steering);
  EXPECT_GT(fit.alpha_distance, 1.15 * noise.distance);
}

/// Odometry arcs steered up to 0.55 rad with noisy steering, against the model's lock at 0.6:
/// the motion's arcs near the lock are clamped there. The fit leaves out the arcs that could
/// reach it (3 sigma of a first fit) instead of reading the clamp as less noise: over seeds
/// 1-8 it finds 0.184-0.205 for 0.2 with that cut and 0.159-0.182 without it (this seed: 0.184
/// and 0.159).
TEST(CalibrateAckermann, ArcsNearFullLockDoNotBiasTheSteeringNoise) {
  expect_recovered({.distance = 0.02, .steering = 0.2, .max_phi = 0.55}, false, 600);
}

/// Turns on the spot, full-lock and non-finite arcs are no arcs the model reads: too few left is
/// an error that says so.
TEST(CalibrateAckermann, TooFewArcsIsAnError) {
  std::vector<MotionSample> spins(100);
  for (MotionSample& m : spins) m.odometry = m.motion = {0.0, 0.0, 0.5};
  try {
    (void)fit_ackermann_noise(spins, kWheelbase);
    ADD_FAILURE() << "fitted turns on the spot";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("0 of 100"), std::string::npos) << e.what();
  }
  // Arcs that are not finite are no arcs either (one would make the likelihood NaN).
  std::vector<MotionSample> bad = draws({.distance = 0.02, .steering = 0.1}, 100, 3);
  for (MotionSample& m : bad) m.motion.theta = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)fit_ackermann_noise(bad, kWheelbase), Error);
}

}  // namespace
}  // namespace mote::calibrate
