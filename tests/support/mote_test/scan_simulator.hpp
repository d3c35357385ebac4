#pragma once
/// \file
/// Simulated scans for engine tests: ranges ray-cast with Embree from a known pose on a real map,
/// plus Gaussian noise, and a drive through free space that never enters a wall.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote::test {

/// A scanner and a driver on one map; deterministic for a seed.
class ScanSimulator {
 public:
  /// `options` says what stops a ray (by default occupied and unknown cells, as amcl's beam
  /// model reads a map; a laser in the building itself sees through cells nobody mapped).
  ScanSimulator(const OccupancyGrid& grid, std::uint64_t seed, RayCastOptions options = {})
      : caster_(grid, options), rng_(seed) {}

  /// A 180-beam, 180-degree scan from `pose` with range noise sigma (m); 0 noise is exact.
  LaserScan scan_at(const Pose2& pose, double sigma = 0.01, float max_range = 20.0F,
                    int beams = 181) {
    LaserScan scan;
    scan.angle_min = static_cast<float>(-std::numbers::pi / 2);
    scan.angle_increment = static_cast<float>(std::numbers::pi / (beams - 1));
    scan.range_min = 0.05F;
    scan.range_max = max_range;
    for (int b = 0; b < beams; ++b) {
      const double angle = pose.theta + scan.beam_angle(static_cast<std::size_t>(b));
      float r = caster_.cast_one({pose.x, pose.y}, angle, max_range);
      if (r < max_range) r += static_cast<float>(sigma * normal());
      scan.ranges.push_back(r);
    }
    return scan;
  }

  /// The next pose of a robot wandering through free space: forward `step` metres when the way
  /// ahead is clear for a metre, else a turn; a slight random curve keeps it exploring.
  Pose2 drive(const Pose2& pose, double step = 0.3) {
    const double turn = 0.15 * normal();
    for (int attempt = 0; attempt < 32; ++attempt) {
      const double heading = wrap_angle(pose.theta + turn + attempt * 0.4);
      if (caster_.cast_one({pose.x, pose.y}, heading, 10.0F) > step + 1.0) {
        return {pose.x + step * std::cos(heading), pose.y + step * std::sin(heading), heading};
      }
    }
    return {pose.x, pose.y, wrap_angle(pose.theta + std::numbers::pi / 2)};
  }

  /// A standard normal draw (Box-Muller over the test's own generator).
  double normal() {
    const double u1 = (static_cast<double>(rng_() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(rng_() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  RayCaster caster_;
  std::mt19937_64 rng_;
};

/// Euclidean position error, m.
inline double position_error(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}
/// Absolute heading error, rad.
inline double heading_error(const Pose2& a, const Pose2& b) {
  return std::abs(wrap_angle(a.theta - b.theta));
}

}  // namespace mote::test
