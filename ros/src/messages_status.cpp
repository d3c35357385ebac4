/// \file
/// sensor_msgs/LaserScan (to play a recorded log over DDS) and diagnostic_msgs/DiagnosticArray
/// (the localization state).

#include <cstddef>

#include "message_fields.hpp"

namespace mote::ros {

LaserScanMessage to_laser_scan_message(const LaserScan& scan, std::string frame_id) {
  LaserScanMessage m;
  m.header.stamp = to_stamp(scan.stamp);
  m.header.frame_id = std::move(frame_id);
  m.angle_min = scan.angle_min;
  m.angle_increment = scan.angle_increment;
  const std::size_t last = scan.ranges.empty() ? 0 : scan.ranges.size() - 1;
  m.angle_max = static_cast<float>(scan.beam_angle(last));
  m.range_min = scan.range_min;
  m.range_max = scan.range_max;
  m.ranges = scan.ranges;
  return m;
}

std::string encode_laser_scan(const LaserScanMessage& msg) {
  detail::CdrWriter w;
  detail::write_header(w, msg.header);
  for (const float v : {msg.angle_min, msg.angle_max, msg.angle_increment, msg.time_increment,
                        msg.scan_time, msg.range_min, msg.range_max}) {
    w.f32(v);
  }
  w.f32_sequence(msg.ranges);
  w.f32_sequence(msg.intensities);
  return std::move(w).finish();
}

std::string encode_diagnostics(const DiagnosticArray& msg) {
  detail::CdrWriter w;
  detail::write_header(w, msg.header);
  w.sequence(msg.status.size());
  for (const DiagnosticStatus& s : msg.status) {
    w.u8(s.level);
    w.string(s.name);
    w.string(s.message);
    w.string(s.hardware_id);
    w.sequence(s.values.size());
    for (const KeyValue& kv : s.values) {
      w.string(kv.key);
      w.string(kv.value);
    }
  }
  return std::move(w).finish();
}

}  // namespace mote::ros
