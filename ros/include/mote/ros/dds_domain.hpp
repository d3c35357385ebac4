#pragma once
/// \file
/// The DDS domain a ROS 2 graph runs on.

namespace mote::ros {

/// The ROS_DOMAIN_ID environment variable (0 when unset or empty); throws ConfigError unless it
/// is a whole number from 0 to 232, as ROS 2 accepts.
[[nodiscard]] int ros_domain_id();

}  // namespace mote::ros
