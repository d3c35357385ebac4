// Thrun et al., Probabilistic Robotics, table 5.6 (sample_motion_model_odometry) and ROS amcl's
// omnidirectional variant. The per-update increments are computed once in double; the
// per-particle loop is float, branch-free and uses only fast_math, so it vectorizes; it is
// compiled per instruction set and dispatched (isa_target.hpp).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mote/core/isa_target.hpp"
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

// One update's increment and noise, in float, for the per-particle loops.
struct OdometryDraw {
  float rot1, trans, rot2;
  float sd_rot1, sd_trans, sd_rot2;
};

struct OmniDraw {
  float trans, rot, bearing;
  float sd_trans, sd_rot, sd_strafe;
};

MOTE_ALWAYS_INLINE void odometry_loop(const OdometryDraw& d, const ParticleView& p,
                                      std::size_t begin, std::size_t end, const RngStream& rng) {
  float* x = p.x;
  float* y = p.y;
  float* theta = p.theta;
  for (std::size_t i = begin; i < end; ++i) {
    const std::array<float, 4> n = rng.normal4(static_cast<std::uint32_t>(i));
    const float rot1_hat = d.rot1 - d.sd_rot1 * n[0];
    const float trans_hat = d.trans - d.sd_trans * n[1];
    const float rot2_hat = d.rot2 - d.sd_rot2 * n[2];
    const SinCos heading = fast_sin_cos(theta[i] + rot1_hat);  // table 5.6, lines 8-10
    x[i] += trans_hat * heading.cos;
    y[i] += trans_hat * heading.sin;
    theta[i] = fast_wrap_angle(theta[i] + rot1_hat + rot2_hat);
  }
}

MOTE_ALWAYS_INLINE void omni_loop(const OmniDraw& d, const ParticleView& p, std::size_t begin,
                                  std::size_t end, const RngStream& rng) {
  float* x = p.x;
  float* y = p.y;
  float* theta = p.theta;
  for (std::size_t i = begin; i < end; ++i) {
    const std::array<float, 4> n = rng.normal4(static_cast<std::uint32_t>(i));
    const float trans_hat = d.trans + d.sd_trans * n[0];
    const float rot_hat = d.rot + d.sd_rot * n[1];
    const float strafe_hat = d.sd_strafe * n[2];
    const SinCos b = fast_sin_cos(theta[i] + d.bearing);
    x[i] += trans_hat * b.cos + strafe_hat * b.sin;
    y[i] += trans_hat * b.sin - strafe_hat * b.cos;
    theta[i] = fast_wrap_angle(theta[i] + rot_hat);
  }
}

MOTE_ISA_VARIANTS(odometry, odometry_loop,
                  (const OdometryDraw& d, const ParticleView& p, std::size_t begin, std::size_t end,
                   const RngStream& rng),
                  (d, p, begin, end, rng))
MOTE_ISA_VARIANTS(omni, omni_loop,
                  (const OmniDraw& d, const ParticleView& p, std::size_t begin, std::size_t end,
                   const RngStream& rng),
                  (d, p, begin, end, rng))

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
  const OdometryDraw draw{static_cast<float>(rot1),
                          static_cast<float>(trans),
                          static_cast<float>(rot2),
                          stddev(alpha1 * r1 * r1 + alpha2 * trans * trans),
                          stddev(alpha3 * trans * trans + alpha4 * (r1 * r1 + r2 * r2)),
                          stddev(alpha1 * r2 * r2 + alpha2 * trans * trans)};
  static const auto kernel =
      detail::pick_variant(&odometry_generic, &odometry_avx2, &odometry_avx512);
  kernel(draw, p, begin, end, rng);
}

void OmniModel::sample(const Odometry& u, const ParticleView& p, std::size_t begin, std::size_t end,
                       const RngStream& rng) const {
  const double dx = u.current.x - u.previous.x;
  const double dy = u.current.y - u.previous.y;
  const double trans = std::hypot(dx, dy);
  const double rot = wrap_angle(u.current.theta - u.previous.theta);
  // Bearing of the displacement relative to the old heading (amcl_odom.cpp, omni model).
  const OmniDraw draw{static_cast<float>(trans),
                      static_cast<float>(rot),
                      static_cast<float>(wrap_angle(std::atan2(dy, dx) - u.previous.theta)),
                      stddev(alpha3 * trans * trans + alpha1 * rot * rot),
                      stddev(alpha4 * rot * rot + alpha2 * trans * trans),
                      stddev(alpha1 * rot * rot + alpha5 * trans * trans)};
  static const auto kernel = detail::pick_variant(&omni_generic, &omni_avx2, &omni_avx512);
  kernel(draw, p, begin, end, rng);
}

}  // namespace mote
