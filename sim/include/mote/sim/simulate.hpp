#pragma once
/// \file
/// A deterministic robot simulator for testing and demonstrating localization: a differential
/// drive robot wanders between random goals through the free space of an occupancy grid, a
/// planar laser is ray cast from its true pose, and its odometry drifts the way wheel odometry
/// does. The output is what a real run records: a CARMEN log (odometry + scans) and the true
/// poses as a TUM trajectory. Same map, config and seed give byte-identical files.

#include <cstdint>
#include <filesystem>
#include <numbers>
#include <optional>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/logs/tum.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote::sim {

/// Odometry error per scan interval, applied to the true increment (translation d, m, and
/// rotation r, rad) in the robot frame: d' = d (1 + translation_bias) + N(0, (translation d)^2),
/// r' = r (1 + rotation_bias) + N(0, (rotation r)^2 + (rotation_per_metre d)^2). The errors
/// accumulate as odometry integrates (Thrun et al., Probabilistic Robotics, section 5.4).
struct OdometryNoise {
  double translation = 0.02;  ///< std of the translation error per metre driven (m/m)
  double rotation = 2.0 * std::numbers::pi / 180.0;  ///< std of the heading error per rad turned
  double rotation_per_metre = 0.5 * std::numbers::pi / 180.0;  ///< heading std per metre (rad/m)
  double translation_bias = 0.005;  ///< systematic scale error of distance (fraction)
  double rotation_bias = 0.01;      ///< systematic scale error of rotation (fraction)
};

/// Odometry noise drawn from the odometry motion model itself (Thrun et al., table 5.6, lines
/// 5-7, amcl's conventions as mote's sampler uses them), so a calibration has known alphas to
/// recover: the true increment (rot1, trans, rot2) becomes rot1 (1 + rotation_bias) + n1,
/// trans (1 + translation_bias) + n2, rot2 (1 + rotation_bias) + n3 with var n1 = alpha1 rot1^2
/// + alpha2 trans^2, var n2 = alpha3 trans^2 + alpha4 (rot1^2 + rot2^2), var n3 = alpha1 rot2^2
/// + alpha2 trans^2, one draw per scan interval.
struct OdometryAlphaNoise {
  double alpha1 = 0.05, alpha2 = 0.01, alpha3 = 0.02, alpha4 = 0.005;
  double translation_bias = 0.0;  ///< systematic scale error of distance (fraction)
  double rotation_bias = 0.0;     ///< systematic scale error of rotation (fraction)
};

/// Range readings drawn from the beam model's mixture (Thrun et al., table 6.1, eqs. 6.4-6.11)
/// around the ray-cast range z*: N(z*, sigma_hit^2), an exponential truncated to [0, z*], the
/// maximum range, or uniform on [0, max_range), with these weights (they must sum to 1).
struct RangeMixture {
  double z_hit = 0.8, z_short = 0.1, z_max = 0.05, z_rand = 0.05;
  double sigma_hit = 0.05;    ///< m
  double lambda_short = 0.5;  ///< 1/m
};

/// Everything the simulator can vary; the defaults give a modest indoor robot with a SICK-like
/// 181-beam, 180 degree laser.
struct SimulationConfig {
  double seconds = 60.0;          ///< s, simulated time
  std::uint64_t seed = 1;         ///< random seed: start pose, goals and all noise
  double start_stamp = 0.0;       ///< s, time stamp of the first scan
  std::optional<Pose2> start;     ///< true start pose (m, rad); default: a random clear cell
  double speed = 0.5;             ///< m/s, cruise speed
  double max_turn_rate = 1.0;     ///< rad/s
  double robot_radius = 0.2;      ///< m, the true pose always keeps this far from blocking cells
  double path_clearance = 0.35;   ///< m, planned paths keep this far (>= robot_radius)
  double scan_rate = 10.0;        ///< Hz, scans (and odometry samples) per second
  int beams = 181;                ///< beams per scan, spread evenly over fov
  double fov = std::numbers::pi;  ///< rad, first beam at -fov/2, last at +fov/2
  float max_range = 20.0F;        ///< m, readings that hit nothing report this
  float range_min = 0.05F;        ///< m, the laser's minimum range
  double range_noise = 0.02;      ///< m, std of the Gaussian range error
  double dropout_probability = 0.01;   ///< chance a reading is replaced by max_range
  double short_probability = 0.01;     ///< chance a reading is a uniform short one (clutter)
  Pose2 sensor_offset{0.1, 0.0, 0.0};  ///< laser mounting pose in the robot frame (m, rad)
  OdometryNoise odometry;              ///< odometry drift model
  /// When set, the odometry noise is the motion model's (replaces `odometry`).
  std::optional<OdometryAlphaNoise> odometry_alphas;
  /// When set, ranges are drawn from the beam mixture (replaces range_noise,
  /// dropout_probability and short_probability).
  std::optional<RangeMixture> range_mixture;
};

/// A simulated run: one frame per scan with the drifting odometry, and the true base pose at
/// the same stamps. frames[k].stamp == truth[k].stamp; odometry starts at the true start pose.
struct Simulation {
  std::vector<logs::ScanFrame> frames;   ///< odometry + scan per scan time, in time order
  std::vector<logs::StampedPose> truth;  ///< true robot base pose per scan, map frame (m, rad)
  std::size_t goals_reached = 0;         ///< goals the robot arrived at
};

/// Runs the simulator on a map. Throws ConfigError on invalid config values, or when the map
/// has no cell with robot_radius of free space around it.
[[nodiscard]] Simulation simulate(const OccupancyGrid& map, const SimulationConfig& config = {});

/// Paths of the files write_simulation produces.
struct SimulationFiles {
  std::filesystem::path log;           ///< `sim.clf`, CARMEN log (ODOM + ROBOTLASER1)
  std::filesystem::path ground_truth;  ///< `sim.gt.tum`, true poses stamped like the scans
  /// `sim.noise.yaml`: the noise the log was drawn with, in the config's names (the oracle of a
  /// calibration); written when odometry_alphas or range_mixture is set, else empty.
  std::filesystem::path noise;
};

/// Writes `sim.clf`, `sim.gt.tum` (and `sim.noise.yaml`) into `directory` (created if missing).
/// Throws mote::Error if a file cannot be written.
SimulationFiles write_simulation(const Simulation& sim, const std::filesystem::path& directory,
                                 const SimulationConfig& config = {});

/// The bundled office floor plan (20 m x 15 m, 5 cm cells), `floorplan.yaml`: the source tree
/// copy when it exists, else the installed one (<datadir>/mote). Throws mote::Error if neither
/// exists.
[[nodiscard]] std::filesystem::path bundled_map_path();

}  // namespace mote::sim
