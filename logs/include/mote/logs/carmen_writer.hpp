#pragma once
/// \file
/// Writing CARMEN logs (the format open_carmen_log reads): one `ODOM` and one `ROBOTLASER1` line
/// per scan frame. ROBOTLASER1 is used for every scan because, unlike FLASER, it records the
/// start angle, field of view, angular resolution, maximum range and the laser pose, so any
/// scan geometry round-trips. Numbers are written in their shortest exact decimal form, so
/// reading the log back gives the same stamps, odometry and ranges bit for bit.

#include <filesystem>
#include <iosfwd>
#include <span>
#include <string>

#include "mote/core/pose.hpp"
#include "mote/logs/scan_source.hpp"

namespace mote::logs {

/// Fields of a CARMEN line that ScanFrame does not hold.
struct CarmenWriteOptions {
  std::string hostname = "mote";  ///< the hostname field (one word, no spaces)
  int laser_type = 0;             ///< ROBOTLASER1 laser_type (CARMEN: 0 = SICK LMS)
  double accuracy = 0.01;         ///< ROBOTLASER1 accuracy field, m
};

/// Robot velocities written beside a pose.
struct CarmenVelocity {
  double tv = 0.0;  ///< m/s, forward speed
  double rv = 0.0;  ///< rad/s, turn rate
};

/// Writes `ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp`.
void write_carmen_odom(std::ostream& out, double stamp, const Pose2& odometry,
                       CarmenVelocity velocity = {}, const CarmenWriteOptions& options = {});

/// Writes one ROBOTLASER1 line for a frame: laser pose = odometry (+) scan.sensor_pose, field
/// of view = (n - 1) * angle_increment, no remissions. Throws ConfigError on an empty scan,
/// a non-finite number or a negative range (the reader would reject them).
void write_carmen_robotlaser(std::ostream& out, const ScanFrame& frame,
                             CarmenVelocity velocity = {}, const CarmenWriteOptions& options = {});

/// Writes a whole log: a comment header, then ODOM and ROBOTLASER1 lines per frame, with the
/// velocities taken from consecutive odometry poses.
void write_carmen_log(std::ostream& out, std::span<const ScanFrame> frames,
                      const CarmenWriteOptions& options = {});

/// Writes a log file. Throws mote::Error if the file cannot be written.
void write_carmen_log(const std::filesystem::path& path, std::span<const ScanFrame> frames,
                      const CarmenWriteOptions& options = {});

}  // namespace mote::logs
