// beluga_mote: mote's side of bench/compare-beluga. mote's Localizer with nav2_amcl's defaults
// (nav2_defaults(): amcl's 1 + sum pz^3, fixed alphas, no recovery) on the scenario of
// beluga_scenario.hpp, the particle count fixed (min = max: KLD cannot change it), every frame an
// update, a resample at every update, and everything else the filter does per update by default
// (the clusters, the refined estimate's scan match, the localization state) left in.
//
//   beluga_mote --map MAP.yaml --model likelihood_field|beam --particles N --threads T
//               --updates U [--beams B] [--ray-casting exact|table]
//
// Prints one JSON object (beluga_scenario.hpp, print_result): the median update time, measured
// around Localizer::update(), its phases as the Localizer reports them (UpdateStats::ms), and
// the final error of the best estimate against the simulated truth.
#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include "beluga_scenario.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/maps/map_loader.hpp"

namespace {

using Clock = std::chrono::steady_clock;
namespace peers = mote::bench::peers;

mote::LocalizerConfig config_for(const peers::RunArgs& args) {
  mote::LocalizerConfig c = mote::nav2_defaults();
  c.laser_model_type =
      args.model == "beam" ? mote::LaserModel::kBeam : mote::LaserModel::kLikelihoodField;
  c.ray_casting = args.ray_casting == "table" ? mote::RayCasting::kTable : mote::RayCasting::kExact;
  c.min_particles = c.max_particles = args.particles;
  c.threads = args.threads;
  c.max_beams = args.beams;
  c.update_min_d = c.update_min_a = 0.0;  // every frame of the drive updates
  c.resample_interval = 1;
  c.resample_ess_fraction = 1.0;  // nav2's already: a resample at every update
  return c;
}

mote::Pose2 pose(const peers::PlainPose& p) { return {p.x, p.y, p.theta}; }

mote::LaserScan laser_scan(const peers::Scenario& s, const peers::Frame& frame) {
  mote::LaserScan scan;
  scan.angle_min = s.scan.angle_min;
  scan.angle_increment = s.scan.angle_increment;
  scan.range_min = s.scan.range_min;
  scan.range_max = s.scan.range_max;
  scan.sensor_pose = pose(s.scan.sensor);
  scan.ranges = frame.ranges;
  return scan;
}

peers::RunResult run(const peers::RunArgs& args, const peers::Scenario& s) {
  const mote::OccupancyGrid map = mote::load_map(args.map);
  const mote::LocalizerConfig config = config_for(args);
  mote::Localizer filter(map, config);
  std::vector<mote::LaserScan> scans;  // converted before the timed loop
  scans.reserve(s.frames.size());
  for (const peers::Frame& f : s.frames) scans.push_back(laser_scan(s, f));

  const peers::Frame& start = s.frames[s.frame(0)];
  filter.initialize(
      pose(start.truth),
      Eigen::Vector3d(peers::kStartVariance[0], peers::kStartVariance[1], peers::kStartVariance[2])
          .asDiagonal());
  filter.update(pose(start.odometry), scans[s.frame(0)]);  // weighs only (kInitialized)

  peers::RunResult r;
  r.peer = "mote";
  r.description = "Localizer, nav2_defaults(), fixed N, resample every update";
  if (config.laser_model_type == mote::LaserModel::kBeam) {
    r.description += std::string(", ") + mote::name_of(config.ray_casting) + " ray casting";
  }
  r.updates.reserve(static_cast<std::size_t>(args.updates));
  for (int k = 1; k <= args.updates; ++k) {
    const std::size_t f = s.frame(static_cast<std::size_t>(k));
    const auto t0 = Clock::now();
    filter.update(pose(s.frames[f].odometry), scans[f]);
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    const mote::UpdateStats& stats = filter.last_update();
    if (stats.outcome != mote::UpdateOutcome::kUpdated || !stats.resampled) {
      throw mote::Error("update " + std::to_string(k) +
                        " did not run the whole filter: " + stats.reason);
    }
    r.updates.push_back({stats.ms.motion, stats.ms.sensor, stats.ms.normalize, stats.ms.resample,
                         stats.ms.estimate, ms});
    r.particles = stats.weighed;
    r.beams = stats.beams;
    r.truth = s.frames[f].truth;
  }
  const mote::Pose2 best = filter.estimate().best().mean;
  r.estimate = {best.x, best.y, best.theta};
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const peers::RunArgs args = peers::parse_args(argc, argv, "beluga_mote", true);
    const peers::Scenario scenario = peers::make_scenario(args.map, args.beams);
    peers::print_result(args, scenario, run(args, scenario));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beluga_mote: %s\n", e.what());
    return 1;
  }
}
