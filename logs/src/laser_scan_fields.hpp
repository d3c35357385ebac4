#pragma once
/// \file
/// sensor_msgs/LaserScan after its header, in the field order of the .msg definition that ROS 1
/// and ROS 2 share: one body for both wire formats, over either byte reader (ByteReader for ROS 1
/// serialization, CdrReader for CDR), which offer the same f32, sequence, skip and position.

#include <cmath>

#include "bag_format.hpp"
#include "mote/core/scan.hpp"

namespace mote::logs::detail {

/// Reads angle_min through range_max, the ranges and the intensities into `scan`; ranges are
/// kept as recorded (NaN and inf too: "no return"), intensities skipped. Throws BagDecodeError
/// for non-finite angles or range limits and for arrays longer than the message.
template <class Reader>
void read_laser_scan_fields(Reader& r, LaserScan& scan) {
  scan.angle_min = r.f32("angle_min");
  (void)r.f32("angle_max");
  scan.angle_increment = r.f32("angle_increment");
  (void)r.f32("time_increment");
  (void)r.f32("scan_time");
  scan.range_min = r.f32("range_min");
  scan.range_max = r.f32("range_max");
  if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment) ||
      !std::isfinite(scan.range_min) || !(scan.range_max > 0.0F)) {
    throw BagDecodeError{r.position(), "LaserScan angles or range limits are not finite"};
  }
  scan.ranges.resize(r.sequence("ranges", 4));
  for (float& range : scan.ranges) range = r.f32("range");
  r.skip(r.sequence("intensities", 4), 4, "intensities");
}

}  // namespace mote::logs::detail
