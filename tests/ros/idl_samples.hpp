#pragma once
/// \file
/// Filling idlc samples (tests/ros/idl) from mote's message structs, for the golden tests.

#include "cyclone_golden.hpp"
#include "geometry_msgs.h"
#include "mote/ros/messages.hpp"
#include "std_msgs.h"

namespace mote::ros::test {

/// The header's fields; the frame id points into `h`.
inline void fill(std_msgs_msg_dds__Header_& out, const Header& h) {
  out.stamp_.sec_ = h.stamp.sec;
  out.stamp_.nanosec_ = h.stamp.nanosec;
  out.frame_id_ = idl_string(h.frame_id);
}

/// A planar pose: z = 0, the rotation about z.
inline geometry_msgs_msg_dds__Pose_ idl_pose(const Pose2& p) {
  const auto q = yaw_quaternion(p.theta);
  return {{p.x, p.y, 0.0}, {q[0], q[1], q[2], q[3]}};
}

}  // namespace mote::ros::test
