#pragma once
/// \file
/// What a live localizer reads from a nav2 params file besides the filter's parameters: the
/// frames, topics and tf it works with, the start pose, and saving the last pose. The names and
/// defaults are nav2_amcl's (amcl_node.cpp, initParameters; the same in Humble, Jazzy and
/// Kilted), so a nav2 params file means what it means to nav2_amcl. load_config reads the
/// filter's keys from the same file and leaves these to read_node_params.

#include <filesystem>
#include <string>
#include <vector>

namespace mote {

/// nav2_amcl's `initial_pose.{x,y,z,yaw}`: metres and radians in the global frame.
struct InitialPoseParams {
  double x = 0.0;    ///< m
  double y = 0.0;    ///< m
  double z = 0.0;    ///< m; read for completeness, a 2D filter does not use it
  double yaw = 0.0;  ///< rad

  friend bool operator==(const InitialPoseParams&, const InitialPoseParams&) = default;
};

/// The live node's parameters, with nav2_amcl's defaults.
struct NodeParams {
  std::string global_frame_id = "map";           ///< the map's frame (REP 105)
  std::string odom_frame_id = "odom";            ///< the odometry's frame
  std::string base_frame_id = "base_footprint";  ///< the robot's frame
  /// The LaserScan topics, as nav2's `scan_topic` names them (relative names resolve in the
  /// node's namespace). A list of topics, each with its own laser (mote's extension: nav2 takes
  /// one), is read from `scan_topic: [front/scan, rear/scan]`.
  std::vector<std::string> scan_topics{"scan"};
  std::string map_topic = "map";  ///< the OccupancyGrid topic
  /// s: map -> odom is stamped this far after the scan it comes from, so that tf consumers can
  /// look it up until the next update (nav2_amcl).
  double transform_tolerance = 1.0;
  bool tf_broadcast = true;        ///< publish map -> odom on /tf
  bool set_initial_pose = false;   ///< start at initial_pose instead of globally
  InitialPoseParams initial_pose;  ///< the start pose set_initial_pose asks for
  /// On a reset, start from /initialpose or set_initial_pose, not from the last known pose.
  bool always_reset_initial_pose = false;
  bool first_map_only = false;            ///< keep the first map, ignore later ones on map_topic
  double save_pose_rate = 0.5;            ///< Hz at which the pose is saved; <= 0: never
  bool initialize_at_saved_pose = false;  ///< start at the pose saved_pose_filepath holds
  std::string saved_pose_filepath = "/tmp/amcl_saved_pose";  ///< where the pose is saved

  friend bool operator==(const NodeParams&, const NodeParams&) = default;
};

/// Reads NodeParams from a nav2 params file (its `amcl: ros__parameters:` section) or a flat
/// YAML map; keys absent from the file keep nav2_amcl's defaults, and the filter's keys are
/// left to load_config (which warns about keys neither reads). `initial_pose` is read as nav2
/// writes it, a map of x, y, z and yaw, or as dotted keys (`initial_pose.x`). A wrong type, an
/// empty frame or topic, a negative or non-finite time or a non-finite pose throws InputError
/// naming the file, the line and the key.
[[nodiscard]] NodeParams read_node_params(const std::filesystem::path& yaml);

/// As read_node_params, from YAML text; `name` stands for the file in messages.
[[nodiscard]] NodeParams parse_node_params(const std::string& yaml_text, const std::string& name);

}  // namespace mote
