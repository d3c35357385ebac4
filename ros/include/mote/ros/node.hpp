#pragma once
/// \file
/// mote::ros::Node: nav2_amcl's job over DDS with no ROS installed. It subscribes to the laser
/// scans, /map, /tf, /tf_static and /initialpose of a ROS 2 graph, runs a Localizer on its own
/// thread and publishes map -> odom on /tf, /amcl_pose, /particle_cloud and the localization
/// state (docs/live.md). Inputs that are malformed or cannot be used are counted and warned
/// about, never fatal; a scan that arrives while an update runs replaces the one waiting (the
/// newest scan wins) and the skipped one is counted.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/engine/localization_state.hpp"
#include "mote/engine/localizer_config.hpp"

namespace mote::ros {

/// What the node subscribes to, publishes and starts from. Names follow nav2_amcl's
/// parameters; the defaults are nav2's, except that an empty base frame means "the child of the
/// odometry frame on /tf", as `mote replay` reads bags.
struct NodeOptions {
  LocalizerConfig config;                        ///< the filter (threads: config.threads)
  std::vector<std::string> scan_topics{"scan"};  ///< scan_topic; several lasers: one update each
  std::string map_topic = "map";                 ///< nav_msgs/OccupancyGrid, transient local
  std::string global_frame = "map";              ///< global_frame_id
  std::string odom_frame = "odom";               ///< odom_frame_id
  std::string base_frame;                        ///< base_frame_id; empty: the child of odom
  double transform_tolerance = 1.0;              ///< s, map -> odom is post-dated by this
  bool tf_broadcast = true;                      ///< publish map -> odom
  std::optional<Pose2> initial_pose;             ///< set_initial_pose / initial_pose.*
  /// Covariance of the initial pose (x m, y m, yaw rad); amcl's initial_cov_xx 0.5 * 0.5 etc.
  Eigen::Matrix3d initial_covariance = Eigen::Vector3d(0.25, 0.25, 0.0685).asDiagonal();
  /// A map_server YAML to use instead of (until) the map topic; empty: wait for the topic.
  std::filesystem::path map_file;
  bool first_map_only = false;  ///< keep the first map; later ones on the topic are ignored
  /// A new map starts at the initial pose (or globally), not at the last pose while tracking.
  bool always_reset_initial_pose = false;
  /// Where the last pose is kept across restarts (empty: nowhere): written atomically every
  /// 1 / save_pose_rate seconds while tracking, read at start when no initial pose is given.
  std::filesystem::path pose_file;
  double save_pose_rate = 0.5;  ///< Hz
  /// s a scan may wait for the odometry at its stamp before it is dropped.
  double scan_wait = 0.5;
  int domain_id = 0;  ///< ROS_DOMAIN_ID
  /// Every warning and notice, one line each (rate-limited per kind); empty: standard error.
  std::function<void(const std::string&)> log;
};

/// What the node has seen and done so far.
struct NodeCounters {
  std::uint64_t scans_received = 0;        ///< scans decoded on every scan topic
  std::uint64_t scans_processed = 0;       ///< scans handed to the filter (update or not moved)
  std::uint64_t updates = 0;               ///< filter updates that ran
  std::uint64_t scans_skipped = 0;         ///< replaced by a newer scan while the filter was busy
  std::uint64_t dropped_no_transform = 0;  ///< no transform base -> the scan's frame
  std::uint64_t dropped_no_odometry = 0;   ///< no odometry at the scan's stamp in time
  std::uint64_t dropped_no_map = 0;        ///< scans before any map arrived
  std::uint64_t malformed = 0;             ///< samples that did not decode, on any topic
  std::uint64_t map_messages = 0;   ///< samples taken off the map topic (each prepared unless a
                                    ///< newer one replaces it while it waits, or it is malformed)
  std::uint64_t maps = 0;           ///< maps prepared and handed to the filter (file or topic)
  std::uint64_t initial_poses = 0;  ///< /initialpose messages taken
  std::uint64_t published = 0;      ///< map -> odom transforms published
  LocalizationState state = LocalizationState::kUncertain;
  double misfit = 0.0;
  Pose2 pose;               ///< the last reported pose (map frame)
  double pose_stamp = 0.0;  ///< s, its scan's stamp
  /// ms from a scan's arrival to its map -> odom being published: p50 and p99 of the
  /// processed scans so far (0 before any). It includes the wait for the odometry at the scan's
  /// stamp on /tf, which is the robot's (a lidar that stamps its scans before it publishes them
  /// has odometry at hand; one that publishes first waits for the next odom -> base).
  double latency_p50_ms = 0.0;
  double latency_p99_ms = 0.0;
  /// ms from the scan's pairing with its odometry to its map -> odom being published: what the
  /// node itself adds (the update, the estimate, the messages).
  double processing_p50_ms = 0.0;
  double processing_p99_ms = 0.0;
};

/// A live localizer on a ROS 2 graph. Starts its threads in the constructor; the destructor
/// (or stop()) ends them within a second and leaves no DDS entity behind.
class Node {
 public:
  /// Joins the DDS domain and starts; throws mote::Error when DDS cannot start, ConfigError for
  /// an invalid config or topic name, InputError for an unreadable map_file.
  explicit Node(NodeOptions options);
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  /// Re-initializes over the map's free space (nav2's reinitialize_global_localization).
  void request_global_localization();
  /// Runs the next update without waiting for motion (nav2's request_nomotion_update).
  void request_nomotion_update();
  /// Stops the threads and leaves the domain; idempotent.
  void stop();
  /// The counts so far (after stop(): the final ones). Thread-safe.
  [[nodiscard]] NodeCounters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  NodeCounters final_counters_;
};

}  // namespace mote::ros
