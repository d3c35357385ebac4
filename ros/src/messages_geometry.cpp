/// \file
/// The localizer's outputs: geometry_msgs/PoseWithCovarianceStamped, tf2_msgs/TFMessage and
/// nav2_msgs/ParticleCloud.

#include <algorithm>
#include <array>
#include <cstddef>

#include "message_fields.hpp"

namespace mote::ros {
namespace {

// PoseWithCovariance.covariance is the 6x6 matrix of (x, y, z, rotation about x, y, z); the
// planar (x, y, yaw) covariance goes into rows and columns 0, 1 and 5.
constexpr std::array<std::size_t, 3> kPlanarAxes = {0, 1, 5};

std::array<double, 36> full_covariance(const std::array<double, 9>& planar) {
  std::array<double, 36> full{};
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c)
      full[6 * kPlanarAxes[r] + kPlanarAxes[c]] = planar[3 * r + c];
  }
  return full;
}

}  // namespace

std::string encode_pose_with_covariance(const PoseWithCovarianceStamped& msg) {
  detail::CdrWriter w;
  detail::write_header(w, msg.header);
  detail::write_planar_pose(w, msg.pose);
  w.f64_array(full_covariance(msg.covariance));
  return std::move(w).finish();
}

std::string encode_tf(std::span<const TransformStamped> transforms) {
  detail::CdrWriter w;
  w.sequence(transforms.size());
  for (const TransformStamped& t : transforms) {
    detail::write_header(w, t.header);
    w.string(t.child_frame_id);
    detail::write_planar_pose(w, t.transform);
  }
  return std::move(w).finish();
}

std::string encode_particle_cloud(const Header& header, std::span<const Particle> particles) {
  detail::CdrWriter w;
  // A Particle takes 8 doubles on the wire.
  w.reserve(64 * particles.size() + 64);
  detail::write_header(w, header);
  w.sequence(particles.size());
  for (const Particle& p : particles) {
    // Pose then weight: 8 float64 in a row, written at once.
    std::array<double, 8> values{};
    const std::array<double, 7> pose = detail::planar_pose(p.pose);
    std::copy(pose.begin(), pose.end(), values.begin());
    values[7] = p.weight;
    w.f64_array(values);
  }
  return std::move(w).finish();
}

}  // namespace mote::ros
