#pragma once
/// \file
/// The ROS 2 messages mote reads, decoded from their CDR bytes (cdr.hpp) into the same records
/// the ROS 1 reader produces. Each throws BagDecodeError with the offset inside the message.

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "bag_messages.hpp"

namespace mote::logs::detail {

/// geometry_msgs/msg/PoseWithCovarianceStamped, planar part (an initial pose).
struct PoseMessage {
  double stamp = 0.0;
  std::string frame_id;
  Pose2 pose;
  /// The 6x6 covariance of (x, y, z, roll, pitch, yaw), row-major (x: 0, y: 7, yaw: 35).
  std::array<double, 36> covariance{};
};

/// sensor_msgs/msg/LaserScan.
[[nodiscard]] ScanMessage decode_laser_scan_cdr(std::string_view bytes);
/// nav_msgs/msg/Odometry.
[[nodiscard]] OdometryMessage decode_odometry_cdr(std::string_view bytes);
/// tf2_msgs/msg/TFMessage.
[[nodiscard]] std::vector<TransformMessage> decode_tf_cdr(std::string_view bytes);
/// geometry_msgs/msg/PoseWithCovarianceStamped.
[[nodiscard]] PoseMessage decode_pose_cdr(std::string_view bytes);

/// The ROS 2 types mote decodes.
enum class Ros2Type { kOther, kLaserScan, kOdometry, kTf, kPose };

/// The type of a ROS 2 type name ("sensor_msgs/msg/LaserScan"), kOther for the rest.
[[nodiscard]] Ros2Type ros2_type(std::string_view name);

/// For a ros2msg schema text (the MCAP "ros2msg" encoding: the message definition, then its
/// dependencies after "====" lines): nullopt when its top-level fields are the ones the decoder
/// of `type` reads in that order, else a description of the first difference.
[[nodiscard]] std::optional<std::string> schema_mismatch(Ros2Type type, std::string_view text);

}  // namespace mote::logs::detail
