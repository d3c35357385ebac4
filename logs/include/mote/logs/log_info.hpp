#pragma once
/// \file
/// What a recorded log holds, for `mote info`: what `ros2 bag info` prints (duration, message
/// counts per topic and type, storage, compression) plus the laser as the replay reads it
/// (beams, field of view, range limits, mounting pose) and the tf frames. Every format mote
/// reads: CARMEN (message types stand in for topics), ROS 1 bags, rosbag2 folders, MCAP, .db3.

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/logs/scan_source.hpp"

namespace mote::logs {

struct TopicCount {
  std::string name;  ///< topic (CARMEN: the message type)
  std::string type;  ///< message type ("sensor_msgs/msg/LaserScan"; CARMEN: empty)
  std::size_t messages = 0;
};

struct LogInfo {
  std::string format;              ///< "CARMEN log", "ROS 1 bag 2.0", "ROS 2 rosbag2 folder", ...
  std::string storage;             ///< "text", "rosbag 2.0", "sqlite3", "mcap"
  std::string compression;         ///< chunk compressions ("lz4", "zstd, lz4"), "none" or ""
  std::string index;               ///< how it was read (MCAP: summary or linear scan)
  std::vector<std::string> files;  ///< the storage files
  double start = 0.0;              ///< s, first message time (record time for ROS)
  double end = 0.0;                ///< s, last message time
  std::string time_source;         ///< what start and end are: "record times", "ipc_timestamp"
  std::size_t messages = 0;
  std::vector<TopicCount> topics;
  std::vector<std::string> frames;  ///< tf edges, "parent -> child" (+ " (static)")
  // The laser, from the frames the replay reads:
  std::size_t scans = 0;     ///< scan frames with odometry
  double scan_first = 0.0;   ///< s, the first scan frame's stamp (ScanFrame::stamp)
  double scan_last = 0.0;    ///< s, the last one's
  std::string stamp_source;  ///< what those stamps are (ScanSource::stamp_source)
  std::size_t beams = 0;     ///< of the first scan
  double angle_min = 0.0;    ///< rad, in the laser frame, first scan
  double angle_max = 0.0;    ///< rad
  double angle_increment = 0.0;
  double range_min = 0.0;  ///< m
  double range_max = 0.0;  ///< m
  std::string range_max_source;
  Pose2 mount;  ///< laser in the base frame, first scan
  std::vector<std::string> warnings;
};

/// Reads the whole log once for its counts and once through its scan source. Throws InputError
/// like the readers.
[[nodiscard]] LogInfo describe_log(const std::filesystem::path& path,
                                   const ReaderOptions& options = {});

/// The table `mote info` prints.
void print_log_info(std::ostream& out, const LogInfo& info);

}  // namespace mote::logs
