/// \file
/// Laser and odometry noise for the simulator.

#include "simulate_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace mote::replay::detail {

LaserScan empty_scan(const SimulationConfig& config, double stamp) {
  LaserScan scan;
  scan.stamp = stamp;
  scan.angle_min = static_cast<float>(-0.5 * config.fov);
  scan.angle_increment =
      config.beams > 1 ? static_cast<float>(config.fov / (config.beams - 1)) : 0.0F;
  scan.range_min = config.range_min;
  scan.range_max = config.max_range;
  scan.sensor_pose = config.sensor_offset;
  return scan;
}

namespace {

/// One reading from the ray cast range `hit` (m) and four uniforms: u[0] picks the mixture
/// component, u[1] places a short reading, u[2], u[3] make the Gaussian (Box-Muller).
float noisy_range(float hit, const std::array<float, 4>& u, const SimulationConfig& config) {
  const double pick = u[0];
  if (pick < config.dropout_probability) return config.max_range;
  if (pick < config.dropout_probability + config.short_probability) {
    // Short readings are uniform between range_min and the true range (unexpected objects).
    return config.range_min + u[1] * std::max(0.0F, hit - config.range_min);
  }
  if (hit >= config.max_range) return config.max_range;  // no return stays no return
  const double noise = config.range_noise * box_muller(u[2], u[3]).a;
  const double r = std::clamp(hit + noise, static_cast<double>(config.range_min),
                              static_cast<double>(config.max_range));
  return static_cast<float>(r);
}

}  // namespace

void simulate_ranges(const RayCaster& caster, const Pose2& truth, const SimulationConfig& config,
                     std::uint64_t scan_index, LaserScan& scan) {
  const Pose2 sensor = compose(truth, scan.sensor_pose);
  const RngStream rng{.seed = config.seed, .step = scan_index, .purpose = kSimRanges};
  scan.ranges.resize(static_cast<std::size_t>(config.beams));
  for (std::size_t b = 0; b < scan.ranges.size(); ++b) {
    const double angle = sensor.theta + scan.beam_angle(b);
    const float hit = caster.cast_one(Point2{sensor.x, sensor.y}, angle, config.max_range);
    scan.ranges[b] = noisy_range(hit, rng.uniform4(static_cast<std::uint32_t>(b)), config);
  }
}

Pose2 noisy_increment(const Pose2& delta, const OdometryNoise& noise, std::uint64_t seed,
                      std::uint64_t scan_index) {
  const RngStream rng{.seed = seed, .step = scan_index, .purpose = kSimOdometry};
  const std::array<float, 4> n = rng.normal4(0);
  const double trans = std::hypot(delta.x, delta.y);
  // Direction of travel in the robot frame; kept, so only length and heading change.
  const double direction = trans > 0.0 ? std::atan2(delta.y, delta.x) : 0.0;
  const double trans_odo =
      trans * (1.0 + noise.translation_bias) + noise.translation * trans * n[0];
  const double rot_std = std::hypot(noise.rotation * delta.theta, noise.rotation_per_metre * trans);
  const double rot_odo = delta.theta * (1.0 + noise.rotation_bias) + rot_std * n[1];
  return {trans_odo * std::cos(direction), trans_odo * std::sin(direction), wrap_angle(rot_odo)};
}

}  // namespace mote::replay::detail
