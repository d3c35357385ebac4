#pragma once
/// \file
/// mote play: a recorded log published over DDS as ROS 2 topics, so that a live localizer (mote
/// node, nav2_amcl, Beluga) can run on it with no robot and no ROS installed. A ROS 2 recording
/// (rosbag2 folder, .mcap, .db3) is published message for message, its CDR bytes unchanged, on
/// its own topics with each topic's QoS as nav2 expects it; a CARMEN log is published as a robot
/// would: /scan (sensor_msgs/LaserScan), odom -> base_link on /tf and base_link -> laser on
/// /tf_static. A map_server YAML is published as nav_msgs/OccupancyGrid on /map (transient
/// local, as nav2's map_server does).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include "mote/logs/scan_source.hpp"

namespace mote::ros {

struct PlayOptions {
  std::filesystem::path log;  ///< ROS 2 recording or CARMEN log
  std::filesystem::path map;  ///< map_server YAML to publish; empty: none
  std::string map_topic = "map";
  /// Playback speed: 1 is the recorded rate, 2 twice as fast; 0 as fast as DDS takes it.
  double rate = 1.0;
  /// s to wait, before the first message, for a reader on each scan topic (0: do not wait).
  double wait_for_readers = 0.0;
  /// s to keep the map and the last messages available after the end (transient local
  /// topics are served to late readers only while the writer lives).
  double linger = 0.0;
  int domain_id = 0;
  logs::ReaderOptions reader;  ///< for CARMEN logs (max range), and lenient reading
  /// Polled between messages: true ends the playback early (SIGINT).
  std::function<bool()> stop_requested;
  /// Progress and notices, one line each; empty: nothing.
  std::function<void(const std::string&)> log_line;
};

/// What a playback published.
struct PlayResult {
  std::map<std::string, std::size_t> messages;  ///< per ROS topic
  double recorded_s = 0.0;                      ///< the log's span of time
  double wall_s = 0.0;                          ///< how long the playback took
  bool stopped = false;                         ///< ended by stop_requested
};

/// Publishes the log (and map) and returns when done. Throws InputError for an unreadable log or
/// map, mote::Error when DDS cannot start.
PlayResult play(const PlayOptions& options);

}  // namespace mote::ros
