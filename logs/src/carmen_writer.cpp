/// \file
/// CARMEN log writing; the line layouts are those carmen_reader.cpp parses (CARMEN's
/// logger/writelog.c): ODOM and ROBOTLASER1, timestamps written twice (ipc and logger).

#include "mote/logs/carmen_writer.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <ostream>
#include <string>
#include <system_error>

#include "mote/core/error.hpp"

namespace mote::logs {
namespace {

/// Appends a number in its shortest form that parses back to the same value (std::to_chars
/// without a precision is exact for round trips).
template <class Real>
void append(std::string& line, Real value) {
  if (!std::isfinite(value)) throw ConfigError("CARMEN writer: non-finite number");
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (ec != std::errc{}) throw ConfigError("CARMEN writer: cannot format a number");
  line.push_back(' ');
  line.append(buffer, end);
}

void append_word(std::string& line, const std::string& word) {
  line.push_back(' ');
  line.append(word);
}

void append_pose(std::string& line, const Pose2& pose) {
  append(line, pose.x);
  append(line, pose.y);
  append(line, pose.theta);
}

/// `ipc_timestamp hostname logger_timestamp`, the tail of every CARMEN message.
void append_stamps(std::string& line, double stamp, const CarmenWriteOptions& options) {
  append(line, stamp);
  append_word(line, options.hostname);
  append(line, stamp);
  line.push_back('\n');
}

void check_ranges(const LaserScan& scan) {
  if (scan.ranges.empty()) throw ConfigError("CARMEN writer: scan has no ranges");
  for (const float r : scan.ranges) {
    if (!(r >= 0.0F) || !std::isfinite(r)) {
      throw ConfigError("CARMEN writer: ranges must be finite and non-negative");
    }
  }
}

/// Forward speed (m/s) and turn rate (rad/s) between two odometry poses dt seconds apart.
CarmenVelocity velocity_between(const ScanFrame& a, const ScanFrame& b) {
  const double dt = b.stamp - a.stamp;
  if (!(dt > 0.0)) return {};
  const Pose2 d = between(a.odometry, b.odometry);
  return {d.x / dt, d.theta / dt};
}

}  // namespace

void write_carmen_odom(std::ostream& out, double stamp, const Pose2& odometry,
                       CarmenVelocity velocity, const CarmenWriteOptions& options) {
  std::string line = "ODOM";
  append_pose(line, odometry);
  append(line, velocity.tv);
  append(line, velocity.rv);
  append(line, 0.0);  // accel
  append_stamps(line, stamp, options);
  out << line;
}

void write_carmen_robotlaser(std::ostream& out, const ScanFrame& frame, CarmenVelocity velocity,
                             const CarmenWriteOptions& options) {
  const LaserScan& scan = frame.scan;
  check_ranges(scan);
  const auto beams = static_cast<float>(scan.ranges.size() - 1);
  std::string line = "ROBOTLASER1 " + std::to_string(options.laser_type);
  append(line, scan.angle_min);
  append(line, beams * scan.angle_increment);  // field of view
  append(line, scan.angle_increment);
  append(line, scan.range_max);
  append(line, options.accuracy);
  line += " 0 " + std::to_string(scan.ranges.size());  // remission_mode, beam count
  line.reserve(line.size() + 10 * scan.ranges.size() + 200);
  for (const float r : scan.ranges) append(line, r);
  line += " 0";  // no remissions
  append_pose(line, compose(frame.odometry, scan.sensor_pose));
  append_pose(line, frame.odometry);
  append(line, velocity.tv);
  append(line, velocity.rv);
  line += " 0 0 0";  // forward_safety, side_safety, turn_axis
  append_stamps(line, frame.stamp, options);
  out << line;
}

void write_carmen_log(std::ostream& out, std::span<const ScanFrame> frames,
                      const CarmenWriteOptions& options) {
  out << "# CARMEN log written by mote\n"
      << "# message formats: ODOM x y theta tv rv accel, ROBOTLASER1 (see carmen_writer.hpp)\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const CarmenVelocity v = k == 0 ? CarmenVelocity{} : velocity_between(frames[k - 1], frames[k]);
    write_carmen_odom(out, frames[k].stamp, frames[k].odometry, v, options);
    write_carmen_robotlaser(out, frames[k], v, options);
  }
}

void write_carmen_log(const std::filesystem::path& path, std::span<const ScanFrame> frames,
                      const CarmenWriteOptions& options) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error("cannot open '" + path.string() + "' for writing");
  write_carmen_log(out, frames, options);
  out.flush();
  if (!out) throw Error("cannot write '" + path.string() + "'");
}

}  // namespace mote::logs
