#pragma once
/// \file
/// How ROS 2 names its topics and types on the DDS wire (rmw_cyclonedds and rmw_fastrtps alike):
/// a ROS topic `/scan` is the DDS topic `rt/scan`, and a message type `sensor_msgs/msg/LaserScan`
/// is the DDS type `sensor_msgs::msg::dds_::LaserScan_`.

#include <string>
#include <string_view>

namespace mote::ros {

/// The DDS topic name of a ROS 2 topic: "rt" + the fully qualified name ("/scan" -> "rt/scan";
/// a relative "scan" is taken as "/scan", as a node in the root namespace resolves it).
/// Throws InputError for an empty name or one with characters ROS 2 does not allow.
[[nodiscard]] std::string dds_topic_name(std::string_view ros_topic);

/// The DDS type name of a ROS 2 type name ("sensor_msgs/msg/LaserScan" ->
/// "sensor_msgs::msg::dds_::LaserScan_"). Throws InputError unless it is "pkg/msg/Name".
[[nodiscard]] std::string dds_type_name(std::string_view ros_type);

}  // namespace mote::ros
