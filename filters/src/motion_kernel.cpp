// The motion kernel of grid localization (Thrun et al., Probabilistic Robotics, section 8.2.3):
// the odometry model's density p(x' | u, x) (table 5.5) evaluated from each heading bin's centre
// to the cells around the expected displacement.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mote/filters/histogram_filter.hpp"

namespace mote {
namespace {

// The odometry increment as (rot1, trans, rot2) with the sampler's conventions and its three
// standard deviations (motion.cpp, table 5.6 lines 5-7), so density and sampler agree.
struct OdometryIncrement {
  double rot1, trans, rot2;
  double sd_rot1, sd_trans, sd_rot2;
};

double rotation_noise(double rot, bool amcl) {
  return amcl ? std::min(std::abs(rot), std::abs(wrap_angle(rot - std::numbers::pi))) : rot;
}

OdometryIncrement increment(const Odometry& u, const OdometryModel& m) {
  const double dx = u.current.x - u.previous.x;
  const double dy = u.current.y - u.previous.y;
  OdometryIncrement inc{};
  inc.trans = std::hypot(dx, dy);
  inc.rot1 = (m.amcl_compatible && inc.trans < 0.01)
                 ? 0.0
                 : wrap_angle(std::atan2(dy, dx) - u.previous.theta);
  inc.rot2 = wrap_angle(u.current.theta - u.previous.theta - inc.rot1);
  const double r1 = rotation_noise(inc.rot1, m.amcl_compatible);
  const double r2 = rotation_noise(inc.rot2, m.amcl_compatible);
  const double t2 = inc.trans * inc.trans;
  // A floor keeps the density finite for noise-free increments (1 mm, 1 mrad).
  inc.sd_rot1 = std::max(std::sqrt(m.alpha1 * r1 * r1 + m.alpha2 * t2), 1e-3);
  inc.sd_trans = std::max(std::sqrt(m.alpha3 * t2 + m.alpha4 * (r1 * r1 + r2 * r2)), 1e-3);
  inc.sd_rot2 = std::max(std::sqrt(m.alpha1 * r2 * r2 + m.alpha2 * t2), 1e-3);
  return inc;
}

double normal_density(double x, double sd) {
  return std::exp(-0.5 * (x / sd) * (x / sd)) / (sd * std::sqrt(2.0 * std::numbers::pi));
}

// Table 5.5 from (0, 0, theta) to (x, y, theta2), times 1 / trans_hat: the Jacobian of the
// change from (rot1, trans, rot2), where the three noises are independent Gaussians, to
// (x, y, theta) (polar coordinates: dx dy = trans dtrans drot1).
double density(const OdometryIncrement& inc, double theta, double x, double y, double theta2) {
  const double trans_hat = std::hypot(x, y);
  const double rot1_hat = wrap_angle(std::atan2(y, x) - theta);
  const double rot2_hat = wrap_angle(theta2 - theta - rot1_hat);
  const double jacobian = 1.0 / std::max(trans_hat, 1e-6);
  return normal_density(wrap_angle(inc.rot1 - rot1_hat), inc.sd_rot1) *
         normal_density(inc.trans - trans_hat, inc.sd_trans) *
         normal_density(wrap_angle(inc.rot2 - rot2_hat), inc.sd_rot2) * jacobian;
}

}  // namespace

std::vector<MotionKernelEntry> GridLocalization::kernel_from(int from, const Odometry& u) const {
  const OdometryIncrement inc = increment(u, config_.motion);
  const double theta = heading_of(from);
  const double k = config_.kernel_sigmas;
  // Expected displacement in the map frame, then in the grid's frame (cells).
  const double mx = inc.trans * std::cos(theta + inc.rot1);
  const double my = inc.trans * std::sin(theta + inc.rot1);
  const double gx = (cos_yaw_ * mx + sin_yaw_ * my) / cell_;
  const double gy = (cos_yaw_ * my - sin_yaw_ * mx) / cell_;
  const double radius = (k * (inc.sd_trans + inc.trans * inc.sd_rot1)) / cell_ + 1.0;
  const double bin = 2.0 * std::numbers::pi / nt_;
  const double dtheta = inc.rot1 + inc.rot2;
  const int t_span =
      std::min(nt_ / 2, static_cast<int>(std::ceil(k * (inc.sd_rot1 + inc.sd_rot2) / bin)) + 1);
  const int t_mid = static_cast<int>(std::lround(dtheta / bin));
  const int s = config_.subsamples;
  std::vector<MotionKernelEntry> out;
  double total = 0.0;
  for (int dt = t_mid - t_span; dt <= t_mid + t_span; ++dt) {
    const int to = ((from + dt) % nt_ + nt_) % nt_;
    for (int dj = static_cast<int>(std::floor(gy - radius));
         dj <= static_cast<int>(std::ceil(gy + radius)); ++dj) {
      for (int di = static_cast<int>(std::floor(gx - radius));
           di <= static_cast<int>(std::ceil(gx + radius)); ++di) {
        double p = 0.0;
        for (int a = 0; a < s; ++a) {
          for (int b = 0; b < s; ++b) {
            const double ox = (di + (a + 0.5) / s - 0.5) * cell_;
            const double oy = (dj + (b + 0.5) / s - 0.5) * cell_;
            const double wx = cos_yaw_ * ox - sin_yaw_ * oy;  // back to the map frame
            const double wy = sin_yaw_ * ox + cos_yaw_ * oy;
            for (int c = 0; c < s; ++c) {
              const double theta2 = theta + (dt + (c + 0.5) / s - 0.5) * bin;
              p += density(inc, theta, wx, wy, theta2);
            }
          }
        }
        if (p > 0.0) out.push_back({di, dj, from, to, p});
        total += p;
      }
    }
  }
  if (!(total > 0.0) || !std::isfinite(total)) {  // all mass between sample points: nearest cell
    out.assign(1, {static_cast<int>(std::lround(gx)), static_cast<int>(std::lround(gy)), from,
                   ((from + t_mid) % nt_ + nt_) % nt_, 1.0});
    return out;
  }
  for (MotionKernelEntry& e : out) e.p /= total;
  return out;
}

MotionKernel GridLocalization::motion_kernel(const Odometry& u) const {
  MotionKernel kernel;
  kernel.by_to.resize(static_cast<std::size_t>(nt_));
  for (int from = 0; from < nt_; ++from) {
    for (const MotionKernelEntry& e : kernel_from(from, u)) {
      kernel.by_to[static_cast<std::size_t>(e.to)].push_back(e);
    }
  }
  return kernel;
}

}  // namespace mote
