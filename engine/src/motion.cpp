// Thrun et al., Probabilistic Robotics, table 5.6 (sample_motion_model_odometry) and ROS amcl's
// omnidirectional variant. The per-update increments are computed once in double; the
// per-particle loop is float, branch-free and uses only fast_math, so it vectorizes.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mote/engine/fast_math.hpp"
#include "mote/engine/motion.hpp"

namespace mote {
namespace {

// amcl's "rotation noise" of a relative angle: driving backwards (rot near +-pi) is a small
// rotation of a reversed robot, not a half turn.
double rotation_noise(double rot, bool amcl) {
  if (!amcl) return rot;
  return std::min(std::abs(rot), std::abs(wrap_angle(rot - std::numbers::pi)));
}

float stddev(double variance) { return static_cast<float>(std::sqrt(std::max(variance, 0.0))); }

}  // namespace

void OdometryModel::sample(const Odometry& u, const ParticleView& p, std::size_t begin,
                           std::size_t end, const RngStream& rng) const {
  const double dx = u.current.x - u.previous.x;
  const double dy = u.current.y - u.previous.y;
  const double trans = std::hypot(dx, dy);
  const double rot1 =
      (amcl_compatible && trans < 0.01) ? 0.0 : wrap_angle(std::atan2(dy, dx) - u.previous.theta);
  const double rot2 = wrap_angle(u.current.theta - u.previous.theta - rot1);
  const double r1 = rotation_noise(rot1, amcl_compatible);
  const double r2 = rotation_noise(rot2, amcl_compatible);
  // Table 5.6, lines 5-7: variances alpha1 rot^2 + alpha2 trans^2 etc.
  const float sd_rot1 = stddev(alpha1 * r1 * r1 + alpha2 * trans * trans);
  const float sd_trans = stddev(alpha3 * trans * trans + alpha4 * (r1 * r1 + r2 * r2));
  const float sd_rot2 = stddev(alpha1 * r2 * r2 + alpha2 * trans * trans);
  const auto f_rot1 = static_cast<float>(rot1);
  const auto f_trans = static_cast<float>(trans);
  const auto f_rot2 = static_cast<float>(rot2);
  float* x = p.x;
  float* y = p.y;
  float* theta = p.theta;
  for (std::size_t i = begin; i < end; ++i) {
    const std::array<float, 4> n = rng.normal4(static_cast<std::uint32_t>(i));
    const float rot1_hat = f_rot1 - sd_rot1 * n[0];
    const float trans_hat = f_trans - sd_trans * n[1];
    const float rot2_hat = f_rot2 - sd_rot2 * n[2];
    const SinCos heading = fast_sin_cos(theta[i] + rot1_hat);  // table 5.6, lines 8-10
    x[i] += trans_hat * heading.cos;
    y[i] += trans_hat * heading.sin;
    theta[i] = fast_wrap_angle(theta[i] + rot1_hat + rot2_hat);
  }
}

void OmniModel::sample(const Odometry& u, const ParticleView& p, std::size_t begin, std::size_t end,
                       const RngStream& rng) const {
  const double dx = u.current.x - u.previous.x;
  const double dy = u.current.y - u.previous.y;
  const double trans = std::hypot(dx, dy);
  const double rot = wrap_angle(u.current.theta - u.previous.theta);
  // Bearing of the displacement relative to the old heading (amcl_odom.cpp, omni model).
  const auto bearing = static_cast<float>(wrap_angle(std::atan2(dy, dx) - u.previous.theta));
  const float sd_trans = stddev(alpha3 * trans * trans + alpha1 * rot * rot);
  const float sd_rot = stddev(alpha4 * rot * rot + alpha2 * trans * trans);
  const float sd_strafe = stddev(alpha1 * rot * rot + alpha5 * trans * trans);
  const auto f_trans = static_cast<float>(trans);
  const auto f_rot = static_cast<float>(rot);
  float* x = p.x;
  float* y = p.y;
  float* theta = p.theta;
  for (std::size_t i = begin; i < end; ++i) {
    const std::array<float, 4> n = rng.normal4(static_cast<std::uint32_t>(i));
    const float trans_hat = f_trans + sd_trans * n[0];
    const float rot_hat = f_rot + sd_rot * n[1];
    const float strafe_hat = sd_strafe * n[2];
    const SinCos b = fast_sin_cos(theta[i] + bearing);
    x[i] += trans_hat * b.cos + strafe_hat * b.sin;
    y[i] += trans_hat * b.sin - strafe_hat * b.cos;
    theta[i] = fast_wrap_angle(theta[i] + rot_hat);
  }
}

}  // namespace mote
