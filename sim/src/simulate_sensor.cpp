/// \file
/// Laser and odometry noise for the simulator.

#include "simulate_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace mote::sim::detail {

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

// One reading of the beam mixture (table 6.1) from the ray cast range `hit`: u[0] picks the
// component, u[1] places a short or random reading, u[2], u[3] make the Gaussian.
float mixture_range(float hit, const std::array<float, 4>& u, const RangeMixture& m,
                    float max_range) {
  const double pick = u[0];
  const double z_star = std::min(hit, max_range);
  double r = max_range;
  if (pick < m.z_hit) {
    r = hit >= max_range ? max_range : z_star + m.sigma_hit * box_muller(u[2], u[3]).a;
  } else if (pick < m.z_hit + m.z_short) {
    // Inverse CDF of the exponential truncated to [0, z*] (eqs. 6.7-6.9).
    const double l = m.lambda_short;
    r = -std::log1p(static_cast<double>(u[1]) * std::expm1(-l * z_star)) / l;
  } else if (pick < m.z_hit + m.z_short + m.z_max) {
    r = max_range;
  } else {
    r = u[1] * static_cast<double>(max_range);
  }
  return static_cast<float>(std::clamp(r, 0.0, static_cast<double>(max_range)));
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
    const std::array<float, 4> u = rng.uniform4(static_cast<std::uint32_t>(b));
    scan.ranges[b] = config.range_mixture
                         ? mixture_range(hit, u, *config.range_mixture, config.max_range)
                         : noisy_range(hit, u, config);
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

Pose2 alpha_increment(const Pose2& delta, const OdometryAlphaNoise& a, std::uint64_t seed,
                      std::uint64_t scan_index) {
  const RngStream rng{.seed = seed, .step = scan_index, .purpose = kSimOdometry};
  const std::array<float, 4> n = rng.normal4(0);
  const double trans = std::hypot(delta.x, delta.y);
  const double rot1 = trans < 0.01 ? 0.0 : std::atan2(delta.y, delta.x);  // amcl's rule
  const double rot2 = wrap_angle(delta.theta - rot1);
  // amcl folds backward motion (rot near +-pi) into a small rotation for the variances.
  auto fold = [](double r) {
    return std::min(std::abs(r), std::abs(wrap_angle(r - std::numbers::pi)));
  };
  const double r1 = fold(rot1), r2 = fold(rot2);
  const double sd1 = std::sqrt(a.alpha1 * r1 * r1 + a.alpha2 * trans * trans);
  const double sd2 = std::sqrt(a.alpha3 * trans * trans + a.alpha4 * (r1 * r1 + r2 * r2));
  const double sd3 = std::sqrt(a.alpha1 * r2 * r2 + a.alpha2 * trans * trans);
  const double o1 = rot1 * (1.0 + a.rotation_bias) + sd1 * n[0];
  const double ot = trans * (1.0 + a.translation_bias) + sd2 * n[1];
  const double o2 = rot2 * (1.0 + a.rotation_bias) + sd3 * n[2];
  return {ot * std::cos(o1), ot * std::sin(o1), wrap_angle(o1 + o2)};
}

}  // namespace mote::sim::detail
