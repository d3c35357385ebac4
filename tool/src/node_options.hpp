#pragma once
// mote node's flags and params file -> ros::NodeOptions.

#include "args.hpp"
#include "mote/ros/node.hpp"

namespace mote::tool {

/// The node's options: the params file first (nav2's or mote's), the flags over it.
[[nodiscard]] ros::NodeOptions node_options(const ParsedArgs& args);

}  // namespace mote::tool
