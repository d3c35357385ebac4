/// \file
/// The simulator's main loop: drive, integrate noisy odometry, cast a scan, once per scan period.

#include "mote/sim/simulate.hpp"

#include <cmath>
#include <string>

#include "mote/core/error.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "simulate_drive.hpp"
#include "simulate_sensor.hpp"

namespace mote::sim {
namespace {

constexpr double kControlPeriod = 0.01;  // s, at most this long per control step

void require(bool ok, const std::string& what) {
  if (!ok) throw ConfigError("simulate: " + what);
}

void validate(const SimulationConfig& c) {
  require(std::isfinite(c.seconds) && c.seconds > 0.0 && c.seconds < 1e7,
          "seconds must be positive");
  require(std::isfinite(c.scan_rate) && c.scan_rate > 0.0 && c.scan_rate <= 1000.0,
          "scan_rate must be in (0, 1000] Hz");
  require(std::isfinite(c.start_stamp), "start_stamp must be finite");
  require(!c.start || is_finite(*c.start), "start pose must be finite");
  require(std::isfinite(c.speed) && c.speed > 0.0, "speed must be positive");
  require(std::isfinite(c.max_turn_rate) && c.max_turn_rate > 0.0,
          "max_turn_rate must be positive");
  require(c.robot_radius >= 0.0 && c.path_clearance >= c.robot_radius &&
              std::isfinite(c.path_clearance),
          "need 0 <= robot_radius <= path_clearance");
  require(c.beams >= 1 && c.beams <= 65536, "beams must be in [1, 65536]");
  require(std::isfinite(c.fov) && c.fov >= 0.0 && c.fov <= 2.0 * std::numbers::pi,
          "fov must be in [0, 2 pi]");
  require(std::isfinite(c.max_range) && c.range_min >= 0.0F && c.max_range > c.range_min,
          "need 0 <= range_min < max_range");
  require(std::isfinite(c.range_noise) && c.range_noise >= 0.0, "range_noise must be >= 0");
  require(c.dropout_probability >= 0.0 && c.short_probability >= 0.0 &&
              c.dropout_probability + c.short_probability <= 1.0,
          "dropout and short probabilities must be >= 0 and sum to at most 1");
  require(is_finite(c.sensor_offset), "sensor_offset must be finite");
  const OdometryNoise& o = c.odometry;
  require(o.translation >= 0.0 && o.rotation >= 0.0 && o.rotation_per_metre >= 0.0 &&
              std::isfinite(o.translation + o.rotation + o.rotation_per_metre),
          "odometry noise must be finite and >= 0");
  require(std::isfinite(o.translation_bias + o.rotation_bias), "odometry bias must be finite");
  if (c.odometry_alphas) {
    const OdometryAlphaNoise& a = *c.odometry_alphas;
    require(a.alpha1 >= 0 && a.alpha2 >= 0 && a.alpha3 >= 0 && a.alpha4 >= 0 &&
                std::isfinite(a.alpha1 + a.alpha2 + a.alpha3 + a.alpha4),
            "odometry alphas must be finite and >= 0");
    require(std::abs(a.translation_bias) < 1 && std::abs(a.rotation_bias) < 1,
            "odometry biases must be in (-1, 1)");
  }
  if (c.range_mixture) {
    const RangeMixture& m = *c.range_mixture;
    require(m.z_hit >= 0 && m.z_short >= 0 && m.z_max >= 0 && m.z_rand >= 0 &&
                std::abs(m.z_hit + m.z_short + m.z_max + m.z_rand - 1.0) < 1e-6,
            "range mixture weights must be >= 0 and sum to 1");
    require(m.sigma_hit > 0 && std::isfinite(m.sigma_hit) && m.lambda_short > 0 &&
                std::isfinite(m.lambda_short),
            "range mixture sigma_hit and lambda_short must be positive");
  }
}

/// Stamp of scan k, made to survive the 9-decimal TUM file exactly. Below 2^53 ns it is rounded
/// to whole nanoseconds: N / 1e9 is the double nearest that decimal, which is what parsing it
/// yields. Above, doubles are more than 1 ns apart, so 9 decimals identify the stamp already.
double scan_stamp(const SimulationConfig& c, std::size_t k) {
  const double t = c.start_stamp + static_cast<double>(k) / c.scan_rate;
  const double ns = t * 1e9;
  return std::abs(ns) < 0x1p53 ? std::round(ns) / 1e9 : t;
}

}  // namespace

Simulation simulate(const OccupancyGrid& map, const SimulationConfig& config) {
  validate(config);
  detail::Driver driver(map, config);
  const RayCaster caster(map);
  const auto scans = static_cast<std::size_t>(std::floor(config.seconds * config.scan_rate + 1e-9));
  const int substeps =
      std::max(1, static_cast<int>(std::ceil(1.0 / (config.scan_rate * kControlPeriod))));
  const double dt = 1.0 / (config.scan_rate * substeps);

  Simulation sim;
  sim.frames.reserve(scans);
  sim.truth.reserve(scans);
  Pose2 odometry = driver.pose();
  for (std::size_t k = 0; k < scans; ++k) {
    const Pose2 before = driver.pose();
    if (k > 0) {
      for (int s = 0; s < substeps; ++s) driver.advance(dt);
      // Odometry integrates noisy increments, so its error grows like real wheel odometry's.
      const Pose2 delta = between(before, driver.pose());
      const Pose2 step =
          config.odometry_alphas
              ? detail::alpha_increment(delta, *config.odometry_alphas, config.seed, k)
              : detail::noisy_increment(delta, config.odometry, config.seed, k);
      odometry = compose(odometry, step);
    }
    logs::ScanFrame frame;
    frame.stamp = scan_stamp(config, k);
    frame.odometry = odometry;
    frame.scan = detail::empty_scan(config, frame.stamp);
    detail::simulate_ranges(caster, driver.pose(), config, k, frame.scan);
    sim.truth.push_back({frame.stamp, driver.pose()});
    sim.frames.push_back(std::move(frame));
  }
  sim.goals_reached = driver.goals_reached();
  return sim;
}

}  // namespace mote::sim
