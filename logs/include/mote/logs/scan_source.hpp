#pragma once
/// \file
/// The record model every recorded-scan reader produces, and the reader interface. Readers stream:
/// they hold one line (CARMEN) or one chunk (ROS bag) at a time, never the whole file.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"

namespace mote::logs {

/// One laser scan with the robot's odometry at the scan time.
struct ScanFrame {
  double stamp = 0.0;  ///< s, the scan's time stamp (CARMEN ipc_timestamp, ROS header.stamp)
  Pose2 odometry;      ///< robot base pose in the odometry frame at `stamp` (m, rad)
  LaserScan scan;      ///< ranges; scan.sensor_pose is the laser mounting pose in the base frame
};

/// What a reader has consumed so far.
struct ReadStats {
  std::size_t records_read = 0;     ///< well-formed records used (lines, bag messages)
  std::size_t records_ignored = 0;  ///< well-formed records of types/topics the reader skips
  std::size_t records_skipped = 0;  ///< malformed records skipped (lenient mode only)
  std::size_t bytes_skipped = 0;    ///< bytes of input in skipped records, or after a stop
  std::string first_error;          ///< message of the first malformed record, empty if none
  /// Problems that did not stop the read, one line each ("FILE: PLACE: PROBLEM"): an MCAP file
  /// cut short while recording is read up to its last complete record.
  std::vector<std::string> warnings;
};

/// The FLASER/RLASER maximum range used when a log gives nothing to infer it from, m: SICK LMS
/// lasers report 81.83 m (8183 cm, the largest code) for "no return".
inline constexpr float kCarmenDefaultMaxRange = 81.83F;

/// Options for every reader; each reader uses the fields that concern it.
struct ReaderOptions {
  /// Skip malformed records and count them in ReadStats instead of throwing InputError. A bag
  /// whose record framing breaks stops there; what was read before is kept.
  bool lenient = false;
  /// CARMEN FLASER/RLASER range_max (the no-return reading), m; ROBOTLASER1 records its own.
  /// nullopt: inferred from the log's first 200 moving scans (NoReturnEstimator, no_return.hpp),
  /// which the reader holds back until then: still one pass over the file.
  std::optional<float> carmen_max_range;
  /// ROS bag: topic of sensor_msgs/LaserScan; empty = the first connection of that type (ROS 1)
  /// or the only such topic (ROS 2; several are an InputError listing them).
  std::string scan_topic;
  /// ROS bag: topic of nav_msgs/Odometry; empty = the first connection of that type (ROS 1) or
  /// the only one (ROS 2), or, when the bag has none, the tf transform odom_frame -> base.
  std::string odom_topic;
  /// ROS bag: the odometry frame used when odometry comes from tf.
  std::string odom_frame = "odom";
  /// ROS bag: the robot's base frame; empty = the child frame of the odometry (the topic's
  /// child_frame_id, or the child of odom_frame on tf).
  std::string base_frame;
  /// ROS bag: largest chunk (uncompressed) a reader agrees to allocate, bytes.
  std::size_t max_chunk_bytes = std::size_t{128} << 20U;
};

/// A stream of scan frames in recording order.
class ScanSource {
 public:
  virtual ~ScanSource() = default;
  /// The next frame, or nullopt at the end. Throws InputError on malformed input unless lenient.
  [[nodiscard]] virtual std::optional<ScanFrame> next() = 0;
  /// Counts so far.
  [[nodiscard]] virtual ReadStats stats() const = 0;
  /// Where the frames' scan.range_max comes from (recorded, given or inferred, and how), for
  /// reports. Meaningful once next() has returned a frame.
  [[nodiscard]] virtual std::string range_max_source() const {
    return "recorded in the log's scan messages";
  }
  /// What the frames' stamps are, for reports that print times: the scans' own "header.stamp"
  /// for ROS (a bag's record times, which `mote info`'s duration spans, can differ by hours);
  /// CARMEN: "ipc_timestamp".
  [[nodiscard]] virtual std::string stamp_source() const { return "header.stamp"; }
};

/// Opens a CARMEN log (.clf, .log). Throws InputError if the file cannot be opened.
[[nodiscard]] std::unique_ptr<ScanSource> open_carmen_log(const std::filesystem::path& path,
                                                          const ReaderOptions& options = {});

/// Opens a ROS 1 bag (format 2.0). Throws InputError if unreadable or not a bag.
[[nodiscard]] std::unique_ptr<ScanSource> open_ros_bag(const std::filesystem::path& path,
                                                       const ReaderOptions& options = {});

/// Opens a ROS 2 recording: a rosbag2 folder (metadata.yaml and its sqlite3 or MCAP storage
/// files, in order), a lone .mcap file or a lone .db3 file. Throws InputError.
[[nodiscard]] std::unique_ptr<ScanSource> open_ros2_bag(const std::filesystem::path& path,
                                                        const ReaderOptions& options = {});

/// Opens a log by its extension: .clf/.log -> CARMEN, .bag -> ROS 1 bag, .mcap/.db3 or a folder
/// with metadata.yaml -> ROS 2; else InputError.
[[nodiscard]] std::unique_ptr<ScanSource> open_scan_log(const std::filesystem::path& path,
                                                        const ReaderOptions& options = {});

}  // namespace mote::logs
