#pragma once
/// \file
/// 2D rigid poses (SE(2)) in metres and radians, angles wrapped to (-pi, pi].

#include <cmath>
#include <numbers>

namespace mote {

/// Wraps an angle in radians to (-pi, pi].
[[nodiscard]] inline double wrap_angle(double angle) noexcept {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double wrapped = std::remainder(angle, kTwoPi);  // in [-pi, pi]
  if (wrapped <= -std::numbers::pi) wrapped += kTwoPi;
  return wrapped;
}

/// A pose in the plane: position in metres, heading in radians (wrapped to (-pi, pi]).
struct Pose2 {
  double x = 0.0;      ///< m
  double y = 0.0;      ///< m
  double theta = 0.0;  ///< rad

  friend bool operator==(const Pose2&, const Pose2&) = default;
};

/// True when every component is finite.
[[nodiscard]] inline bool is_finite(const Pose2& p) noexcept {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

/// a (+) b: b expressed in a's frame, mapped into the frame a lives in.
[[nodiscard]] inline Pose2 compose(const Pose2& a, const Pose2& b) noexcept {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, wrap_angle(a.theta + b.theta)};
}

/// The inverse transform: compose(inverse(a), a) is the identity.
[[nodiscard]] inline Pose2 inverse(const Pose2& a) noexcept {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {-c * a.x - s * a.y, s * a.x - c * a.y, wrap_angle(-a.theta)};
}

/// The relative transform from a to b, expressed in a's frame: compose(a, between(a, b)) == b.
[[nodiscard]] inline Pose2 between(const Pose2& a, const Pose2& b) noexcept {
  return compose(inverse(a), b);
}

}  // namespace mote
