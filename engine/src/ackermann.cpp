// Kinematic bicycle model for car-like robots (see AckermannModel in motion.hpp for the math).
// An odometry increment is read as one circular arc of length s and steering angle phi; noise
// perturbs (s, phi), the physical inputs of a car, and each particle follows its own arc.

#include <algorithm>
#include <cmath>

#include "mote/engine/fast_math.hpp"
#include "mote/engine/motion.hpp"

namespace mote {
namespace {

// sin(h) / h, with the Taylor series near 0 where the quotient loses precision.
float sinc(float h, float sin_h) {
  const float h2 = h * h;
  const float series = 1.0F - h2 * (1.0F / 6 - h2 / 120);
  return std::abs(h) < 1e-3F ? series : sin_h / h;
}

}  // namespace

// The arc through the increment (dx, dy, dtheta) in the previous body frame: the chord has
// length 2 R sin(dtheta / 2) and s = R dtheta, so s = chord * (dtheta / 2) / sin(dtheta / 2).
AckermannArc ackermann_arc(const Pose2& d, double wheelbase, double max_steering) noexcept {
  const double chord = std::hypot(d.x, d.y);
  const double half = 0.5 * d.theta;
  const double ratio = std::abs(half) < 1e-6 ? 1.0 : half / std::sin(half);
  const double forward = d.x >= 0.0 ? 1.0 : -1.0;
  const double s = forward * chord * ratio;
  const double phi = std::abs(s) < 1e-9 ? 0.0 : std::atan(wheelbase * d.theta / s);
  return {s, std::clamp(phi, -max_steering, max_steering)};
}

void AckermannModel::sample(const Odometry& u, const ParticleView& p, std::size_t begin,
                            std::size_t end, const RngStream& rng) const {
  const AckermannArc arc = ackermann_arc(between(u.previous, u.current), wheelbase, max_steering);
  const auto sd_s = static_cast<float>(std::sqrt(alpha_distance) * std::abs(arc.length));
  const auto sd_phi =
      static_cast<float>(std::sqrt(alpha_steering * arc.steering * arc.steering + steering_floor));
  const auto s0 = static_cast<float>(arc.length);
  const auto phi0 = static_cast<float>(arc.steering);
  const auto inv_l = static_cast<float>(1.0 / wheelbase);
  const auto max_phi = static_cast<float>(max_steering);
  float* x = p.x;
  float* y = p.y;
  float* theta = p.theta;
  for (std::size_t i = begin; i < end; ++i) {
    const std::array<float, 4> n = rng.normal4(static_cast<std::uint32_t>(i));
    const float s = s0 + sd_s * n[0];
    const float phi = std::clamp(phi0 + sd_phi * n[1], -max_phi, max_phi);
    const SinCos steer = fast_sin_cos(phi);
    const float dtheta = s * steer.sin / steer.cos * inv_l;  // s tan(phi) / L
    const float half = 0.5F * dtheta;
    const float chord = s * sinc(half, fast_sin_cos(half).sin);
    const SinCos heading = fast_sin_cos(theta[i] + half);  // chord direction: mid-arc heading
    x[i] += chord * heading.cos;
    y[i] += chord * heading.sin;
    theta[i] = fast_wrap_angle(theta[i] + dtheta);
  }
}

}  // namespace mote
