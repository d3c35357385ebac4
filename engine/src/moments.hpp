#pragma once
// Weighted first and second moments of poses with a circular heading (engine-internal).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>

#include "mote/engine/estimate.hpp"

namespace mote::detail {

// Sums for the weighted mean: w, w x, w y, w cos(theta), w sin(theta), count.
struct FirstMoments {
  std::array<double, 5> s{};
  std::size_t count = 0;
  Pose2 first;  // the first particle added: the mean of a set without positive weight

  // Adds one particle given the cosine and sine of its heading.
  void add(double w, double x, double y, double cos_theta, double sin_theta, double theta) {
    if (count == 0) first = {x, y, theta};
    ++count;
    if (!(w > 0.0)) return;  // no weight, no contribution: 0 * NaN would be NaN
    s[0] += w;
    s[1] += w * x;
    s[2] += w * y;
    s[3] += w * cos_theta;
    s[4] += w * sin_theta;
  }
  friend FirstMoments operator+(FirstMoments a, const FirstMoments& b) {
    if (a.count == 0) a.first = b.first;
    for (std::size_t k = 0; k < a.s.size(); ++k) a.s[k] += b.s[k];
    a.count += b.count;
    return a;
  }
  [[nodiscard]] Pose2 mean() const {
    if (!(s[0] > 0.0)) return first;
    return {s[1] / s[0], s[2] / s[0], std::atan2(s[4], s[3])};
  }
};

// theta - mean wrapped to (-pi, pi] for theta and mean within [-3 pi, 3 pi] (the store keeps
// headings in (-pi, pi]); branch-free so that loops calling it vectorize.
[[nodiscard]] inline double heading_residual(double theta, double mean) {
  constexpr double kPi = std::numbers::pi;
  double d = theta - mean;
  for (int step = 0; step < 2; ++step) {
    d = d > kPi ? d - 2 * kPi : d;
    d = d <= -kPi ? d + 2 * kPi : d;
  }
  return d;
}

// Sums of w r r^T for residuals r = (dx, dy, wrapped dtheta): the 6 upper-triangle entries.
struct SecondMoments {
  std::array<double, 6> s{};

  void add(double w, const Pose2& mean, double x, double y, double theta) {
    if (!(w > 0.0)) return;  // as FirstMoments::add
    const double r[3] = {x - mean.x, y - mean.y, heading_residual(theta, mean.theta)};
    s[0] += w * r[0] * r[0];
    s[1] += w * r[0] * r[1];
    s[2] += w * r[0] * r[2];
    s[3] += w * r[1] * r[1];
    s[4] += w * r[1] * r[2];
    s[5] += w * r[2] * r[2];
  }
  friend SecondMoments operator+(SecondMoments a, const SecondMoments& b) {
    for (std::size_t k = 0; k < a.s.size(); ++k) a.s[k] += b.s[k];
    return a;
  }
  [[nodiscard]] Eigen::Matrix3d covariance(double total_weight) const {
    Eigen::Matrix3d c;
    c << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
    return c / total_weight;
  }
};

}  // namespace mote::detail
