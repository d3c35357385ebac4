/// \file
/// Stamps and the fields several messages share.

#include <cmath>
#include <limits>

#include "message_fields.hpp"

namespace mote::ros {

Stamp to_stamp(double seconds) noexcept {
  constexpr double kMin = std::numeric_limits<std::int32_t>::min();
  constexpr double kMax = std::numeric_limits<std::int32_t>::max();
  if (std::isnan(seconds)) return {};
  double whole = std::floor(seconds);
  if (whole < kMin) return {std::numeric_limits<std::int32_t>::min(), 0};
  if (whole > kMax) return {std::numeric_limits<std::int32_t>::max(), 999'999'999U};
  auto nanosec = static_cast<std::int64_t>(std::llround((seconds - whole) * 1e9));
  if (nanosec >= 1'000'000'000) {
    if (whole == kMax) return {std::numeric_limits<std::int32_t>::max(), 999'999'999U};
    whole += 1.0;
    nanosec -= 1'000'000'000;
  }
  return {static_cast<std::int32_t>(whole), static_cast<std::uint32_t>(nanosec)};
}

double to_seconds(Stamp stamp) noexcept {
  return static_cast<double>(stamp.sec) + 1e-9 * static_cast<double>(stamp.nanosec);
}

namespace detail {

void write_stamp(CdrWriter& w, Stamp stamp) {
  w.i32(stamp.sec);
  w.u32(stamp.nanosec);
}

void write_header(CdrWriter& w, const Header& header) {
  write_stamp(w, header.stamp);
  w.string(header.frame_id);
}

std::array<double, 7> planar_pose(const Pose2& pose) {
  // Position (x, y, 0), then the unit quaternion (x, y, z, w) of a rotation by theta about z,
  // as tf2's setRPY(0, 0, theta) makes it.
  return {pose.x, pose.y, 0.0, 0.0, 0.0, std::sin(0.5 * pose.theta), std::cos(0.5 * pose.theta)};
}

void write_planar_pose(CdrWriter& w, const Pose2& pose) { w.f64_array(planar_pose(pose)); }

}  // namespace detail
}  // namespace mote::ros
