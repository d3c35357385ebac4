// calibrate(): the log's frames at known poses (a reference, or the filter's own estimates)
// become beam, endpoint-distance and odometry-increment samples; the fits turn them into a
// config. Without a reference, localization and fitting alternate until the fit settles.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>

#include "calibrate_refine.hpp"
#include "calibrate_rounds.hpp"
#include "calibrate_score.hpp"
#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/beams.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/logs/tum.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote::calibrate {
namespace {

using detail::effective_range_max;
using detail::endpoint_distance;
using detail::endpoint_fit;
using detail::for_fit_beams;
using detail::PosedFrame;
using detail::read_frames;

using Clock = std::chrono::steady_clock;

bool moved_enough(const Pose2& from, const Pose2& to, const LocalizerConfig& c) {
  const Pose2 d = between(from, to);
  return std::hypot(d.x, d.y) > c.update_min_d || std::abs(d.theta) > c.update_min_a;
}

// The checks that stop a calibration before any fit: a log without odometry, or one with too
// few updates (frames the filter's motion gate lets through) to fit from.
void check_log(const std::vector<logs::ScanFrame>& frames, const CalibrationOptions& o) {
  const std::string name = o.log.string();
  if (frames.empty()) throw Error(name + ": no scans: log too short to calibrate from");
  bool any_motion = false;
  std::size_t updates = 1;
  Pose2 last = frames.front().odometry;
  for (const logs::ScanFrame& f : frames) {
    const Pose2 d = between(frames.front().odometry, f.odometry);
    any_motion = any_motion || std::hypot(d.x, d.y) > 1e-9 || std::abs(d.theta) > 1e-9;
    if (moved_enough(last, f.odometry, o.config)) {
      ++updates;
      last = f.odometry;
    }
  }
  if (!any_motion) {
    throw Error(name +
                ": no odometry (every scan's odometry pose is the same): nothing to fit "
                "the motion model from");
  }
  if (updates < o.min_scans) {
    throw Error(name + ": log too short to calibrate from: " + std::to_string(updates) +
                " scans past the motion gate, at least " + std::to_string(o.min_scans) + " needed");
  }
}

// Reference poses at the frames the filter's motion gate would update on.
std::vector<PosedFrame> reference_poses(const std::vector<logs::ScanFrame>& frames,
                                        const CalibrationOptions& o) {
  const std::vector<logs::StampedPose> ref = logs::sort_by_stamp(logs::read_tum(o.reference));
  std::vector<PosedFrame> posed;
  std::optional<Pose2> last;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (last && !moved_enough(*last, frames[k].odometry, o.config)) continue;
    const auto m = logs::match_reference(ref, frames[k].stamp, logs::kReferenceMatchTolerance);
    if (!m) continue;
    posed.push_back({k, m->pose, true, {}});
    last = frames[k].odometry;
  }
  if (posed.size() < o.min_scans) {
    throw Error(o.reference.string() + ": only " + std::to_string(posed.size()) +
                " reference poses match the log's scans, at least " + std::to_string(o.min_scans) +
                " needed");
  }
  return posed;
}

// One localization from global initialization; the poses after the filter converged (its best
// cluster within 0.2 m for 10 updates in a row). Throws when it never does.
std::vector<PosedFrame> localize(const OccupancyGrid& map,
                                 const std::vector<logs::ScanFrame>& frames,
                                 const CalibrationOptions& o, const LocalizerConfig& config,
                                 int round) {
  constexpr double kConvergedStd = 0.2;  // m
  constexpr int kConvergedRun = 10;
  Localizer filter(map, config);
  filter.initialize_global();
  std::vector<PosedFrame> posed;
  int run = 0;
  bool converged = false;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    filter.update(frames[k].odometry, frames[k].scan);
    if (o.progress) o.progress(round, k + 1, frames.size());
    if (!filter.last_update().ran()) continue;
    const PoseEstimate& best = filter.estimate().best();
    const double spread = std::sqrt(best.covariance(0, 0) + best.covariance(1, 1));
    run = spread < kConvergedStd ? run + 1 : 0;
    converged = converged || run >= kConvergedRun;
    if (converged) posed.push_back({k, best.mean, true, {}});
  }
  if (!converged || posed.size() < o.min_scans) {
    throw Error(o.log.string() + ": the filter never converged (round " +
                std::to_string(round + 1) +
                ": its best cluster never stayed within 0.2 m for 10 updates with " +
                std::to_string(o.min_scans) + " updates left); no config written");
  }
  return posed;
}

struct Samples {
  std::vector<BeamSample> beams;
  std::vector<double> distances;
  std::vector<MotionSample> motion;
  std::vector<BeamSample> filter_beams;  ///< the beams the filter itself uses, for the correlation
};

// The beams the filter weighs a scan by (select_beams with the config's selection), with their
// place in that selection: the correlation that matters is the one between the beams the
// filter multiplies, at its spacing, not at the sensor fits' denser one.
void collect_filter_beams(const RayCaster& caster, const LaserScan& scan, const Pose2& sensor,
                          std::size_t scan_index, const LocalizerConfig& c, double range_max,
                          std::vector<BeamSample>& out) {
  BeamSet set;
  select_beams(scan,
               {.max_beams = c.max_beams,
                .range_min = c.laser_min_range,
                .range_max = c.laser_max_range,
                .keep_max_range = c.laser_model_type == LaserModel::kBeam},
               set);
  for (std::size_t k = 0; k < set.size(); ++k) {
    const double expected = caster.cast_one({sensor.x, sensor.y}, sensor.theta + set.angle[k],
                                            static_cast<float>(range_max));
    out.push_back(
        {std::min<double>(set.range[k], range_max), std::min(expected, range_max), scan_index, k});
  }
}

Samples collect(const OccupancyGrid& map, const RayCaster& caster, const DistanceField& field,
                const std::vector<logs::ScanFrame>& frames, const std::vector<PosedFrame>& posed,
                const CalibrationOptions& o, double range_max) {
  Samples s;
  const double max_d = o.config.laser_likelihood_max_dist;
  for (std::size_t p = 0; p < posed.size(); ++p) {
    if (!posed[p].usable) continue;
    const logs::ScanFrame& f = frames[posed[p].frame];
    if (p > 0 && posed[p - 1].usable) {
      const logs::ScanFrame& prev = frames[posed[p - 1].frame];
      s.motion.push_back({between(prev.odometry, f.odometry),
                          between(posed[p - 1].pose, posed[p].pose), posed[p - 1].covariance,
                          posed[p].covariance, posed[p - 1].pose.theta});
    }
    const Pose2 sensor = compose(posed[p].pose, f.scan.sensor_pose);
    collect_filter_beams(caster, f.scan, sensor, p, o.config, range_max, s.filter_beams);
    for_fit_beams(f.scan, o.beams_per_scan, [&](std::size_t b, double z) {
      const double angle = sensor.theta + f.scan.beam_angle(b);
      const double expected =
          caster.cast_one({sensor.x, sensor.y}, angle, static_cast<float>(range_max));
      s.beams.push_back({std::min(z, range_max), std::min(expected, range_max)});
      if (z < range_max)
        s.distances.push_back(endpoint_distance(map, field, sensor, angle, z, max_d));
    });
  }
  return s;
}

// The filter's poses re-estimated from their own scans (calibrate_refine.hpp), with the
// likelihood field as the config holds it (clamped: too sharp a field has no basin, too wide
// a one no precision).
void refine(std::vector<PosedFrame>& posed, const std::vector<logs::ScanFrame>& frames,
            const RayCaster& caster, const BeamMixture& beam, const CalibrationOptions& o,
            double range_max) {
  constexpr double kMinInliers = 0.5;  // a pose that explains fewer readings is in a wrong basin
  const double sigma = std::clamp(beam.sigma_hit, 0.03, 0.1);
  const double z_hit = std::clamp(beam.z_hit, 0.3, 0.95);
  std::vector<detail::Refined> refined(posed.size());
  // Each pose on its own: the result does not depend on the thread count.
  par::for_each_chunk(posed.size(), 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const LaserScan& scan = frames[posed[k].frame].scan;
      const auto step =
          std::max<std::size_t>(1, scan.ranges.size() / static_cast<std::size_t>(o.beams_per_scan));
      refined[k] = detail::refine_pose(caster, scan, posed[k].pose, z_hit, sigma, range_max, step);
    }
  });
  for (std::size_t k = 0; k < posed.size(); ++k) {
    posed[k].pose = refined[k].pose;
    posed[k].covariance = refined[k].covariance;
    posed[k].usable = refined[k].inliers >= kMinInliers;
  }
}

// A tracking run from `start` (its frame and pose) to the end of the log; the estimate at
// every update.
std::vector<PosedFrame> track(const OccupancyGrid& map, const std::vector<logs::ScanFrame>& frames,
                              const CalibrationOptions& o, const LocalizerConfig& config,
                              const PosedFrame& start, int run) {
  constexpr double kSigmaXy = 0.1;      // m
  constexpr double kSigmaTheta = 0.05;  // rad
  Localizer filter(map, config);
  filter.initialize(start.pose, Eigen::Vector3d(kSigmaXy * kSigmaXy, kSigmaXy * kSigmaXy,
                                                kSigmaTheta * kSigmaTheta)
                                    .asDiagonal());
  std::vector<PosedFrame> posed;
  for (std::size_t k = start.frame; k < frames.size(); ++k) {
    filter.update(frames[k].odometry, frames[k].scan);
    if (o.progress) o.progress(run, k + 1, frames.size());
    if (filter.last_update().ran()) posed.push_back({k, filter.estimate().best().mean, true, {}});
  }
  return posed;
}

// The online noise's margin by the scans' fit at the estimates (MarginTrial), each trial a
// tracking run with the final config from `start`.
void choose_margin(const OccupancyGrid& map, const DistanceField& field,
                   const std::vector<logs::ScanFrame>& frames, const CalibrationOptions& o,
                   double range_max, const PosedFrame& start, CalibrationResult& result) {
  const CalibrationRound& last = result.rounds.back();
  const FieldMixture scoring = detail::scoring_field(last);
  int run = static_cast<int>(result.rounds.size());
  // Two seeds per margin: one run's fit varies by about 0.001 nats between seeds, the steps
  // near the best differ by a few times that, and a margin that loses one seed's track must
  // not win on the other's.
  constexpr int kSeeds = 2;
  const MarginScorer score = [&](double margin) {
    LocalizerConfig c = result.config;
    c.motion_noise_margin = margin;
    if (o.particles > 0) c.min_particles = c.max_particles = o.particles;
    std::array<double, kSeeds> fits{};
    MarginTrial trial;
    for (double& fit : fits) {
      const std::vector<PosedFrame> posed = track(map, frames, o, c, start, run++);
      const MarginTrial t = endpoint_fit(map, field, frames, posed, o, range_max, scoring);
      fit = t.fit;
      trial.poses += t.poses;
      ++c.seed;
    }
    const auto [low, high] = std::minmax_element(fits.begin(), fits.end());
    trial.fit = std::accumulate(fits.begin(), fits.end(), 0.0) / kSeeds;
    trial.spread = 0.5 * (*high - *low);
    return trial;
  };
  result.margins = search_margin(score, std::clamp(o.config.motion_noise_margin, 1.0, 64.0));
  result.config.motion_noise_margin = best_margin(result.margins).margin;
}

}  // namespace

CalibrationResult calibrate(const CalibrationOptions& options) {
  const auto start = Clock::now();
  options.config.validate();
  const OccupancyGrid map = load_map(options.map);
  const std::vector<logs::ScanFrame> frames = read_frames(options);
  check_log(frames, options);
  const RayCaster caster(map);
  const DistanceField field(
      map, {.unknown_is_obstacle = false,
            .max_distance = static_cast<float>(options.config.laser_likelihood_max_dist)});
  const double range_max = effective_range_max(frames.front(), options.config);

  CalibrationResult result;
  result.with_reference = !options.reference.empty();
  result.scans = frames.size();
  result.config = options.config;
  result.start = options.config;
  const int rounds = result.with_reference ? 1 : std::max(1, options.max_rounds);
  PosedFrame track_start;  // the last round's first pose: where the margin trials start
  for (int round = 0; round < rounds; ++round) {
    std::vector<PosedFrame> posed;
    if (result.with_reference) {
      posed = reference_poses(frames, options);
    } else {
      posed = localize(map, frames, options, result.config, round);
      refine(posed, frames, caster,
             result.rounds.empty() ? BeamMixture{} : result.rounds.back().beam.params, options,
             range_max);
    }
    if (posed.empty())
      throw Error(options.log.string() + ": no pose to fit from; no config written");
    track_start = posed.front();
    Samples s = collect(map, caster, field, frames, posed, options, range_max);
    CalibrationRound r;
    r.poses = posed.size();
    r.beam = fit_beam_mixture(s.beams, range_max);
    r.field = fit_likelihood_field(s.distances, range_max);
    r.correlation = fit_beam_correlation(s.filter_beams, range_max, r.beam.params.sigma_hit);
    r.odometry = fit_odometry_noise(s.motion, !result.with_reference);
    if (options.config.odom_model_type == OdomModel::kAckermann) {
      r.ackermann = fit_ackermann_noise(s.motion, options.config.wheelbase, !result.with_reference);
    }
    result.samples.motion.clear();
    for (const MotionSample& m : s.motion) result.samples.motion.push_back(motion_residual(m));
    if (!result.rounds.empty())
      detail::measure_change(r, result.rounds.back(), result.samples.motion);
    result.config = detail::apply_fit(options.config, r);
    result.rounds.push_back(r);
    result.samples.beams = std::move(s.beams);
    if (round > 0 && result.rounds.back().largest_change < options.settle) {
      result.settled = true;
      break;
    }
  }
  if (options.search_margin && result.config.adaptive_motion_noise &&
      result.config.odom_model_type == OdomModel::kDiff) {
    choose_margin(map, field, frames, options, range_max, track_start, result);
  }
  result.samples.range_max = range_max;
  result.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace mote::calibrate
