#pragma once
/// \file
/// Hand-written deserializers for the ROS messages the bag reader uses (ROS 1 serialization:
/// little endian, uint32-prefixed strings and arrays, fixed arrays inline). Each throws
/// BagDecodeError with the offset inside the message.

#include <string>
#include <string_view>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"

namespace mote::logs::detail {

/// sensor_msgs/LaserScan (ranges kept as recorded; sensor_pose left at identity).
struct ScanMessage {
  std::string frame_id;
  LaserScan scan;
};

/// nav_msgs/Odometry: the planar part of pose.pose.
struct OdometryMessage {
  double stamp = 0.0;
  std::string frame_id;
  std::string child_frame_id;
  Pose2 pose;
};

/// One geometry_msgs/TransformStamped, planar part.
struct TransformMessage {
  double stamp = 0.0;
  std::string parent;
  std::string child;
  Pose2 pose;  ///< child frame in the parent frame
  /// The child's z axis points down (roll or pitch of pi): angles in the child frame are
  /// mirrored (a -> -a) before `pose` applies.
  bool mirrored = false;
};

/// Frame names without ROS 1's optional leading '/'.
[[nodiscard]] std::string normalize_frame(std::string_view frame);

[[nodiscard]] ScanMessage decode_laser_scan(std::string_view bytes);
[[nodiscard]] OdometryMessage decode_odometry(std::string_view bytes);
/// tf/tfMessage and tf2_msgs/TFMessage share this wire format.
[[nodiscard]] std::vector<TransformMessage> decode_tf(std::string_view bytes);

}  // namespace mote::logs::detail
