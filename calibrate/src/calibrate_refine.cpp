// Scan-to-map alignment of one pose: Nelder-Mead on the beam model's scan log-likelihood, the
// expected ranges ray cast (Embree) at every trial pose.
#include "calibrate_refine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "calibrate_minimize.hpp"

namespace mote::calibrate::detail {
namespace {

// The Laplace approximation of the pose's uncertainty: the inverse Hessian of the negative
// log-likelihood at its minimum, by central differences (5 mm, 5 mm, 2 mrad). Zero when the
// Hessian is not positive definite (a scan that pins nothing down in some direction).
template <class Cost>
PoseCovariance laplace_covariance(Cost& cost, const std::vector<double>& at, double f0) {
  const std::array<double, 3> h{0.005, 0.005, 0.002};
  auto f = [&](int i, double si, int j, double sj) {
    std::vector<double> p = at;
    p[static_cast<std::size_t>(i)] += si * h[static_cast<std::size_t>(i)];
    p[static_cast<std::size_t>(j)] += sj * h[static_cast<std::size_t>(j)];
    return cost(p);
  };
  double H[3][3];
  for (int i = 0; i < 3; ++i) {
    const double hi = h[static_cast<std::size_t>(i)];
    H[i][i] = (f(i, 1, i, 0) - 2 * f0 + f(i, -1, i, 0)) / (hi * hi);
    for (int j = 0; j < i; ++j) {
      const double hj = h[static_cast<std::size_t>(j)];
      H[i][j] = H[j][i] =
          (f(i, 1, j, 1) - f(i, 1, j, -1) - f(i, -1, j, 1) + f(i, -1, j, -1)) / (4 * hi * hj);
    }
  }
  // Inverse by cofactors.
  const double c00 = H[1][1] * H[2][2] - H[1][2] * H[2][1];
  const double c01 = H[1][2] * H[2][0] - H[1][0] * H[2][2];
  const double c02 = H[1][0] * H[2][1] - H[1][1] * H[2][0];
  const double det = H[0][0] * c00 + H[0][1] * c01 + H[0][2] * c02;
  const bool definite = H[0][0] > 0 && H[0][0] * H[1][1] - H[0][1] * H[1][0] > 0 && det > 0;
  if (!definite) return {};
  PoseCovariance c;
  c.xx = c00 / det;
  c.xy = (H[0][2] * H[2][1] - H[0][1] * H[2][2]) / det;
  c.yy = (H[0][0] * H[2][2] - H[0][2] * H[2][0]) / det;
  c.tt = (H[0][0] * H[1][1] - H[0][1] * H[1][0]) / det;
  return c;
}

}  // namespace

Refined refine_pose(const RayCaster& caster, const LaserScan& scan, const Pose2& start,
                    double z_hit, double sigma, double range_max, std::size_t step) {
  const double floor = (1.0 - z_hit) / range_max;
  const double norm = z_hit / (std::sqrt(2.0 * std::numbers::pi) * sigma);
  // The readings the fit uses and their beams' angles, cast together at each trial pose (one
  // scan in 16-wide packets: several times the rate of one ray at a time).
  std::vector<double> readings;
  std::vector<float> angles;
  for (std::size_t b = step / 2; b < scan.ranges.size(); b += step) {
    const double z = scan.ranges[b];
    if (!(z >= scan.range_min) || z >= range_max) continue;
    readings.push_back(z);
    angles.push_back(static_cast<float>(scan.beam_angle(b)));
  }
  std::vector<float> expected(readings.size());
  std::size_t inside = 0;
  auto cost = [&](const std::vector<double>& p) {
    inside = 0;
    const auto x = static_cast<float>(start.x + p[0]);
    const auto y = static_cast<float>(start.y + p[1]);
    const auto theta = static_cast<float>(start.theta + p[2]);
    caster.cast({std::span(&x, 1), std::span(&y, 1), std::span(&theta, 1), angles, scan.sensor_pose,
                 static_cast<float>(range_max)},
                expected);
    double sum = 0;
    for (std::size_t k = 0; k < readings.size(); ++k) {
      const double e = readings[k] - static_cast<double>(expected[k]);
      sum -= std::log(norm * std::exp(-0.5 * e * e / (sigma * sigma)) + floor);
      inside += std::abs(e) < 3 * sigma ? 1U : 0U;
    }
    return sum;
  };
  // Offsets from the start, bounded: a refinement, not a search for a lost robot. Resolved to
  // 0.1 mm and 0.1 mrad: two orders below the poses' own uncertainty (the Laplace covariance
  // below, 1-1.5 cm on a laser of a few cm), where the search by function values alone spent
  // its whole budget of 400 scan casts on six poses in ten.
  constexpr double kMetre = 1e-4, kRadian = 1e-4;
  const std::vector<Bounded> box{{0.0, -0.3, 0.3, false, kMetre},
                                 {0.0, -0.3, 0.3, false, kMetre},
                                 {0.0, -0.15, 0.15, false, kRadian}};
  int evaluations = 0;
  const std::vector<double> best = minimize(cost, box, 400, evaluations);
  const double at_best = cost(best);  // and the inlier count at the result
  Refined r{
      {start.x + best[0], start.y + best[1], wrap_angle(start.theta + best[2])},
      readings.empty() ? 0.0 : static_cast<double>(inside) / static_cast<double>(readings.size()),
      {}};
  r.covariance = laplace_covariance(cost, best, at_best);
  return r;
}

}  // namespace mote::calibrate::detail
