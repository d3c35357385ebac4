// The fits' standard errors (observed information): exact on a Gaussian, and on odometry
// increments drawn from table 5.6 the spread the estimates really have over repeated draws.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "calibrate_minimize.hpp"  // calibrate/src: the minimizer's internal header
#include "mote/calibrate/calibrate.hpp"

namespace mote::calibrate {
namespace {

// -log N(x_i; mu, var) summed: the information of mu is n / var, of var n / (2 var^2).
TEST(StandardErrors, AreTheInverseInformationOfAGaussian) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> draw(1.5, 0.4);
  std::vector<double> x(2000);
  for (double& v : x) v = draw(rng);
  double mean = 0, var = 0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  for (double v : x) var += (v - mean) * (v - mean) / static_cast<double>(x.size());
  auto nll = [&](const std::vector<double>& p) {
    double s = 0;
    for (double v : x) s += 0.5 * ((v - p[0]) * (v - p[0]) / p[1] + std::log(p[1]));
    return s;
  };
  const std::vector<detail::Bounded> box{{0, -10, 10, false}, {1, 1e-6, 100}};
  const std::vector<double> se = detail::standard_errors(nll, {mean, var}, box);
  const double n = static_cast<double>(x.size());
  EXPECT_NEAR(se[0], std::sqrt(var / n), 0.01 * std::sqrt(var / n));
  EXPECT_NEAR(se[1], var * std::sqrt(2 / n), 0.01 * var * std::sqrt(2 / n));
}

TEST(StandardErrors, AParameterAtItsBoundIsHeldAndGetsZero) {
  auto f = [](const std::vector<double>& p) { return (p[0] - 2) * (p[0] - 2) + p[1]; };
  const std::vector<detail::Bounded> box{{0, -10, 10, false}, {1, 1e-6, 1}};
  const std::vector<double> se = detail::standard_errors(f, {2.0, 1e-6}, box);
  EXPECT_NEAR(se[0], std::sqrt(0.5), 1e-4);  // f'' = 2: the inverse Hessian is 1/2
  EXPECT_EQ(se[1], 0.0);
}

// Increments of a robot that drives and turns, odometry drawn around them by table 5.6 (var
// rot1 = a1 rot1^2 + a2 trans^2, var trans = a3 trans^2 + a4 (rot1^2 + rot2^2)).
std::vector<MotionSample> draw_increments(const std::array<double, 4>& a, std::size_t n,
                                          std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> trans(0.05, 0.4), turn(-0.6, 0.6);
  std::normal_distribution<double> unit(0, 1);
  std::vector<MotionSample> out(n);
  for (MotionSample& s : out) {
    const double t = trans(rng), r1 = turn(rng), r2 = turn(rng);
    s.motion = {t * std::cos(r1), t * std::sin(r1), r1 + r2};
    const double o1 = r1 + std::sqrt(a[0] * r1 * r1 + a[1] * t * t) * unit(rng);
    const double ot = t + std::sqrt(a[2] * t * t + a[3] * (r1 * r1 + r2 * r2)) * unit(rng);
    const double o2 = r2 + std::sqrt(a[0] * r2 * r2 + a[1] * t * t) * unit(rng);
    s.odometry = {ot * std::cos(o1), ot * std::sin(o1), o1 + o2};
  }
  return out;
}

// The reported standard error is what the estimates' spread over independent logs is: their
// standard deviation over 30 draws (itself known to about 13%) within [0.6, 1.5] of the mean
// reported error, for every alpha and the rotation scale error.
TEST(OdometryStandardErrors, MatchTheSpreadOfTheEstimatesOverDraws) {
  const std::array<double, 4> truth{0.1, 0.02, 0.05, 0.02};
  constexpr int kDraws = 30;
  std::array<double, 5> sum{}, sum_sq{}, reported{};
  for (int d = 0; d < kDraws; ++d) {
    const OdometryFit f =
        fit_odometry_noise(draw_increments(truth, 300, 100U + static_cast<unsigned>(d)));
    const std::array<double, 5> v{f.alphas.alpha1, f.alphas.alpha2, f.alphas.alpha3,
                                  f.alphas.alpha4, f.rotation_bias};
    const std::array<double, 5> se{f.alphas_se.alpha1, f.alphas_se.alpha2, f.alphas_se.alpha3,
                                   f.alphas_se.alpha4, f.rotation_bias_se};
    for (std::size_t i = 0; i < v.size(); ++i) {
      sum[i] += v[i];
      sum_sq[i] += v[i] * v[i];
      reported[i] += se[i] / kDraws;
    }
  }
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double mean = sum[i] / kDraws;
    const double spread = std::sqrt((sum_sq[i] - kDraws * mean * mean) / (kDraws - 1));
    EXPECT_GT(reported[i], 0.0) << i;
    EXPECT_GT(spread / reported[i], 0.6) << "parameter " << i;
    EXPECT_LT(spread / reported[i], 1.5) << "parameter " << i;
  }
}

}  // namespace
}  // namespace mote::calibrate
