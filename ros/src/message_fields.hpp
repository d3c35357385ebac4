#pragma once
/// \file
/// The parts several ROS 2 messages share (std_msgs/Header, geometry_msgs/Pose), written to and
/// read from CDR.

#include <array>

#include "cdr_writer.hpp"
#include "mote/core/pose.hpp"
#include "mote/ros/messages.hpp"

namespace mote::ros::detail {

/// builtin_interfaces/msg/Time.
void write_stamp(CdrWriter& w, Stamp stamp);
/// std_msgs/msg/Header.
void write_header(CdrWriter& w, const Header& header);
/// The 7 float64 of a geometry_msgs/msg/Pose (or Transform: Vector3 and Quaternion have the
/// Point's layout) of a planar pose: position (x, y, 0), orientation the rotation by theta about z.
[[nodiscard]] std::array<double, 7> planar_pose(const Pose2& pose);
/// Writes planar_pose(pose).
void write_planar_pose(CdrWriter& w, const Pose2& pose);

}  // namespace mote::ros::detail
