// The odometry fit between estimated poses (fit_odometry_noise with estimated_poses): the same
// odometry increments, fitted once between exact poses and once between poses with independent
// noise (as the filter's refined poses have), give the same figures up to that noise's cost.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/pose.hpp"
#include "mote/sim/simulate.hpp"

namespace mote::calibrate {
namespace {

// A robot that mostly drives straight and turns on a third of its steps (20-35 cm a step, as
// the simulated robots between 1.5 Hz scans), odometry drawn around each step by table 5.6
// with scale errors, as the simulator draws it.
std::vector<MotionSample> draw_increments(const sim::OdometryAlphaNoise& a, std::size_t n,
                                          std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> trans(0.2, 0.35), turn(-0.5, 0.5), wobble(-0.05, 0.05);
  std::bernoulli_distribution turning(1.0 / 3.0);
  std::normal_distribution<double> unit(0, 1);
  std::vector<MotionSample> out(n);
  for (MotionSample& s : out) {
    const bool turns = turning(rng);
    const double t = trans(rng), r1 = turns ? turn(rng) : wobble(rng);
    const double r2 = turns ? turn(rng) : wobble(rng);
    const double sd1 = std::sqrt(a.alpha1 * r1 * r1 + a.alpha2 * t * t);
    const double sd2 = std::sqrt(a.alpha3 * t * t + a.alpha4 * (r1 * r1 + r2 * r2));
    const double sd3 = std::sqrt(a.alpha1 * r2 * r2 + a.alpha2 * t * t);
    const double o1 = r1 * (1 + a.rotation_bias) + sd1 * unit(rng);
    const double ot = t * (1 + a.translation_bias) + sd2 * unit(rng);
    const double o2 = r2 * (1 + a.rotation_bias) + sd3 * unit(rng);
    s.odometry = {ot * std::cos(o1), ot * std::sin(o1), wrap_angle(o1 + o2)};
    s.motion = {t * std::cos(r1), t * std::sin(r1), wrap_angle(r1 + r2)};
  }
  return out;
}

// The same increments seen between two poses that each carry independent Gaussian noise (m per
// axis, rad).
std::vector<MotionSample> between_noisy_poses(std::vector<MotionSample> samples, double sd_xy,
                                              double sd_theta, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0, 1);
  const auto jitter = [&](const Pose2& p) {
    return Pose2{p.x + sd_xy * unit(rng), p.y + sd_xy * unit(rng),
                 wrap_angle(p.theta + sd_theta * unit(rng))};
  };
  for (MotionSample& s : samples) {
    const Pose2 before = jitter({0, 0, 0});
    s.motion = between(before, jitter(s.motion));
    s.heading_before = before.theta;
  }
  return samples;
}

using Figures = std::array<double, 6>;  // alpha1-4, translation and rotation scale errors

Figures figures(const OdometryFit& f) {
  return {f.alphas.alpha1, f.alphas.alpha2,    f.alphas.alpha3,
          f.alphas.alpha4, f.translation_bias, f.rotation_bias};
}

// The noisy simulated robot's odometry, biased as the biased one's, between poses with 1.5 cm
// and 3 mrad of noise (about the refined poses' on the noisy robot), against the same increments
// between exact poses; means over 8 logs of 1500 increments. Measured (noisy / exact): alpha1
// 1.02, alpha3 0.98, alpha4 0.88, translation scale error 0.040 / 0.045, rotation scale error
// -0.0529 / -0.0496. The fit of the biases and alphas together with the motion's turns (before
// the two stages and along_turns) gave alpha4 0.85 and a rotation scale error of +0.0035, the
// shift this test is about. Not held: alpha2 (0.79 either way), which the direction channel
// fixes and the poses' position noise over steps of 20-35 cm all but mimics (pose_lateral / t^2
// against alpha2 t^2).
TEST(OdometryFitBetweenEstimatedPoses, MatchesTheFitBetweenExactPoses) {
  const sim::OdometryAlphaNoise truth{0.2, 0.05, 0.1, 0.05, 0.05, -0.05};
  constexpr int kDraws = 8;
  Figures exact{}, estimated{};
  for (int d = 0; d < kDraws; ++d) {
    const std::vector<MotionSample> samples =
        draw_increments(truth, 1500, 200U + static_cast<unsigned>(d));
    const Figures e = figures(fit_odometry_noise(samples, false));
    const Figures n = figures(fit_odometry_noise(
        between_noisy_poses(samples, 0.015, 0.003, 300U + static_cast<unsigned>(d)), true));
    for (std::size_t i = 0; i < e.size(); ++i) {
      exact[i] += e[i] / kDraws;
      estimated[i] += n[i] / kDraws;
    }
  }
  EXPECT_NEAR(estimated[0], exact[0], 0.10 * exact[0]) << "alpha1";
  EXPECT_NEAR(estimated[2], exact[2], 0.10 * exact[2]) << "alpha3";
  EXPECT_NEAR(estimated[3], exact[3], 0.15 * exact[3]) << "alpha4";
  EXPECT_NEAR(estimated[4], exact[4], 0.01) << "translation scale error";
  EXPECT_NEAR(estimated[5], exact[5], 0.015) << "rotation scale error";
}

}  // namespace
}  // namespace mote::calibrate
