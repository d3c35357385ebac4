#pragma once
/// \file
/// A planar laser scan as recorded (ROS sensor_msgs/LaserScan semantics).

#include <cstddef>
#include <vector>

#include "mote/core/pose.hpp"

namespace mote {

/// One planar range scan. Beam i points at angle_min + i * angle_increment (rad) in the sensor
/// frame; sensor_pose places the sensor in the robot's base frame. Invalid readings (NaN, inf,
/// negative, below range_min, at or above range_max) are kept here and dropped by the sensor
/// models before decimation (design.md section 3).
struct LaserScan {
  double stamp = 0.0;            ///< s
  float angle_min = 0.0F;        ///< rad, angle of the first beam in the sensor frame
  float angle_increment = 0.0F;  ///< rad between consecutive beams (may be negative)
  float range_min = 0.0F;        ///< m, readings below are invalid
  float range_max = 0.0F;        ///< m, readings at or above are "no return"
  Pose2 sensor_pose;             ///< mounting pose of the sensor in the base frame
  std::vector<float> ranges;     ///< m, one per beam

  [[nodiscard]] std::size_t size() const noexcept { return ranges.size(); }
  /// Angle of beam i in the sensor frame, rad.
  [[nodiscard]] double beam_angle(std::size_t i) const noexcept {
    return static_cast<double>(angle_min) +
           static_cast<double>(i) * static_cast<double>(angle_increment);
  }
};

}  // namespace mote
