// What the node publishes, on the filter thread: map -> odom on /tf (post-dated by
// transform_tolerance, as nav2_amcl does, so that consumers can look it up until the next one),
// /amcl_pose, /particle_cloud, the localization state, and the saved pose.
#include <algorithm>
#include <cmath>

#include "mote/ros/messages.hpp"
#include "node_impl.hpp"
#include "pose_file.hpp"

namespace mote::ros {
namespace {

constexpr auto kDiagnosticsPeriod = std::chrono::seconds(1);  // diagnostic_updater's rate

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

}  // namespace

void Node::Impl::publish_transform(double stamp) {
  if (!options.tf_broadcast) return;
  const TransformStamped t{.header = {.stamp = to_stamp(stamp + options.transform_tolerance),
                                      .frame_id = options.global_frame},
                           .child_frame_id = options.odom_frame,
                           .transform = map_to_odom};
  tf_writer.write(encode_tf(std::span(&t, 1)));
  const std::lock_guard lock(mutex);
  ++counts.published;
}

void Node::Impl::publish_estimate(double stamp) {
  const LocalizationEstimate& e = filter->estimate();
  PoseWithCovarianceStamped pose{
      .header = {.stamp = to_stamp(stamp), .frame_id = options.global_frame},
      .pose = e.refined.pose};
  const Eigen::Matrix3d& c = e.best().covariance;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) pose.covariance[static_cast<std::size_t>(3 * r + k)] = c(r, k);
  }
  pose_writer.write(encode_pose_with_covariance(pose));
  if (cloud_writer.matched() == 0) return;  // a cloud of 100k particles is 6 MB: only on demand
  const ConstParticleView v = filter->particles();
  std::vector<Particle> cloud(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    cloud[i] = {v.pose(i), std::exp(static_cast<double>(v.logw[i]))};
  }
  cloud_writer.write(encode_particle_cloud(pose.header, cloud));
}

void Node::Impl::publish_state(double stamp) {
  const UpdateStats& u = filter->last_update();
  const LocalizationState state = u.state;
  DiagnosticStatus status{.level = state == LocalizationState::kTracking ? DiagnosticStatus::kOk
                                   : state == LocalizationState::kUncertain
                                       ? DiagnosticStatus::kWarn
                                       : DiagnosticStatus::kError,
                          .name = "mote: localization",
                          .message = name_of(state),
                          .hardware_id = "mote",
                          .values = {}};
  NodeCounters c;
  {
    const std::lock_guard lock(mutex);
    c = counts;
  }
  status.values = {{"state", name_of(state)},
                   {"misfit", fixed(u.misfit, 3)},
                   {"particles", std::to_string(u.particles)},
                   {"clusters", std::to_string(filter->estimate().clusters.size())},
                   {"relocalized", std::to_string(u.relocalized)},
                   {"scans_received", std::to_string(c.scans_received)},
                   {"scans_skipped", std::to_string(c.scans_skipped)},
                   {"scans_dropped", std::to_string(c.dropped_no_transform + c.dropped_no_odometry +
                                                    c.dropped_no_map)},
                   {"malformed", std::to_string(c.malformed)}};
  const DiagnosticArray message{
      .header = {.stamp = to_stamp(stamp), .frame_id = options.global_frame}, .status = {status}};
  const std::string bytes = encode_diagnostics(message);
  state_writer.write(bytes);
  if (Clock::now() - last_diagnostics >= kDiagnosticsPeriod) {
    diagnostics_writer.write(bytes);
    last_diagnostics = Clock::now();
  }
}

void Node::Impl::maybe_save_pose(double stamp) {
  if (options.pose_file.empty() || filter->last_update().state != LocalizationState::kTracking) {
    return;
  }
  const auto period = std::chrono::duration<double>(1.0 / options.save_pose_rate);
  if (Clock::now() - last_pose_save < period) return;
  last_pose_save = Clock::now();
  try {
    write_pose_file(options.pose_file, filter->estimate().refined.pose, stamp);
  } catch (const std::exception& e) {
    warnings.warn("pose file", e.what());
  }
}

}  // namespace mote::ros
