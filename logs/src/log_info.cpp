/// \file
/// `mote info`: the scan part through open_scan_log (so it shows what a replay sees), the
/// message counts per format (log_info_counts.cpp), and the table.

#include "mote/logs/log_info.hpp"

#include <cmath>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <sstream>

#include "log_info_counts.hpp"

namespace mote::logs {
namespace {

void add_scans(const std::filesystem::path& path, const ReaderOptions& options, LogInfo& info) {
  const std::unique_ptr<ScanSource> source = open_scan_log(path, options);
  while (const std::optional<ScanFrame> f = source->next()) {
    info.scan_last = f->stamp;
    if (info.scans++ > 0) continue;
    info.scan_first = f->stamp;
    const LaserScan& s = f->scan;
    info.beams = s.size();
    info.angle_min = s.angle_min;
    info.angle_increment = s.angle_increment;
    info.angle_max = s.beam_angle(s.size() == 0 ? 0 : s.size() - 1);
    info.range_min = s.range_min;
    info.range_max = s.range_max;
    info.mount = s.sensor_pose;
  }
  info.range_max_source = source->range_max_source();
  info.stamp_source = source->stamp_source();
  const ReadStats stats = source->stats();
  info.warnings.insert(info.warnings.end(), stats.warnings.begin(), stats.warnings.end());
}

std::string degrees(double rad) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << rad * 180.0 / std::numbers::pi << " deg";
  return s.str();
}

void row(std::ostream& out, const std::string& key, const std::string& value) {
  out << "  " << std::left << std::setw(18) << key << value << '\n';
}

}  // namespace

LogInfo describe_log(const std::filesystem::path& path, const ReaderOptions& options) {
  LogInfo scans;
  add_scans(path, options, scans);  // first: open_scan_log rejects what is not a log
  LogInfo info = detail::count_messages(path, options);
  info.scans = scans.scans;
  info.scan_first = scans.scan_first;
  info.scan_last = scans.scan_last;
  info.stamp_source = scans.stamp_source;
  info.beams = scans.beams;
  info.angle_min = scans.angle_min;
  info.angle_max = scans.angle_max;
  info.angle_increment = scans.angle_increment;
  info.range_min = scans.range_min;
  info.range_max = scans.range_max;
  info.range_max_source = scans.range_max_source;
  info.mount = scans.mount;
  info.warnings = scans.warnings;
  return info;
}

void print_log_info(std::ostream& out, const LogInfo& info) {
  // Both spans say which clock they read: a bag's record times and its scans' header stamps,
  // which mote replay prints, can be hours apart (the DIS bag: 6,300 s).
  std::ostringstream duration;
  duration << std::fixed << std::setprecision(3) << info.end - info.start << " s of "
           << info.time_source << " (from " << info.start << " to " << info.end << ")";
  std::ostringstream scan_stamps;
  scan_stamps << std::fixed << std::setprecision(3) << info.scan_first << " to " << info.scan_last
              << " (" << info.stamp_source << ", the times mote replay prints)";
  out << "log\n";
  for (const std::string& f : info.files) row(out, "file", f);
  row(out, "format", info.format);
  row(out, "storage", info.storage + (info.index.empty() ? "" : ", " + info.index));
  if (!info.compression.empty()) row(out, "compression", info.compression);
  row(out, "duration", duration.str());
  row(out, "messages", std::to_string(info.messages));
  out << "topics\n";
  for (const TopicCount& t : info.topics) {
    out << "  " << std::left << std::setw(24) << t.name << std::right << std::setw(8) << t.messages
        << "  " << t.type << '\n';
  }
  out << "laser\n";
  row(out, "scans", std::to_string(info.scans) + " with odometry");
  if (info.scans > 0) row(out, "scan stamps", scan_stamps.str());
  row(out, "beams", std::to_string(info.beams));
  const double fov = std::abs(info.angle_increment) * static_cast<double>(info.beams);
  row(out, "field of view",
      degrees(fov) + ", " + degrees(info.angle_min) + " to " + degrees(info.angle_max) +
          " in steps of " + degrees(info.angle_increment));
  std::ostringstream ranges;
  ranges << std::fixed << std::setprecision(3) << info.range_min << " to " << info.range_max
         << " m (range_max " << info.range_max_source << ")";
  row(out, "range", ranges.str());
  std::ostringstream mount;
  mount << std::fixed << std::setprecision(3) << "x " << info.mount.x << " m, y " << info.mount.y
        << " m, yaw " << degrees(info.mount.theta) << " in the base frame";
  row(out, "mount", mount.str());
  if (!info.frames.empty()) {
    out << "frames\n";
    for (const std::string& f : info.frames) out << "  " << f << '\n';
  }
  for (const std::string& w : info.warnings) out << "warning: " << w << '\n';
}

}  // namespace mote::logs
