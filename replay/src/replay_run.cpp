// The replay loop: log -> Localizer -> trajectory, timings, outcome counts and errors.
#include "mote/replay/replay_run.hpp"

#include <Eigen/Core>
#include <chrono>
#include <iomanip>
#include <sstream>
#include <utility>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"

namespace mote::replay {
namespace {

using Clock = std::chrono::steady_clock;

Eigen::Matrix3d initial_covariance(const ReplayOptions& options) {
  const double sxy = options.init_sigma_xy;
  const double st = options.init_sigma_theta;
  return Eigen::Vector3d(sxy * sxy, sxy * sxy, st * st).asDiagonal();
}

// kAuto starts at the reference pose of the first scan (nearest stamp, else the first reference
// pose), so tracking runs can be scored from their first update; without a reference it is global.
// Returns true for a global start.
bool initialize(Localizer& filter, const ReplayOptions& options,
                const std::vector<logs::StampedPose>& sorted_reference, double first_stamp) {
  if (options.init == InitMode::kPose) {
    filter.initialize(options.init_pose, initial_covariance(options));
    return false;
  }
  if (options.init == InitMode::kGlobal || sorted_reference.empty()) {
    filter.initialize_global();
    return true;
  }
  const auto match =
      logs::match_reference(sorted_reference, first_stamp, options.metrics.match_tolerance_s);
  const Pose2 start = match ? match->pose : sorted_reference.front().pose;
  filter.initialize(start, initial_covariance(options));
  return false;
}

void record_update(ReplayResult& result, const Localizer& filter, double stamp,
                   const Pose2& odometry) {
  const UpdateStats& stats = filter.last_update();
  result.trajectory.push_back({stamp, filter.estimate().refined.pose});
  result.particle_trajectory.push_back({stamp, filter.estimate().best().mean});
  result.updates.push_back({.stamp = stamp,
                            .ms = stats.ms,
                            .particles = stats.particles,
                            .weighed = stats.weighed,
                            .beams = stats.beams,
                            .blocked_beams = stats.blocked_beams,
                            .effective_sample_size = stats.effective_sample_size,
                            .tempering = stats.tempering,
                            .log_evidence = stats.log_evidence,
                            .injected = stats.injected,
                            .relocalized = stats.relocalized,
                            .relocalized_locally = stats.relocalized_locally,
                            .resampled = stats.resampled,
                            .alphas = stats.alphas,
                            .state = stats.state,
                            .hit_share = stats.hit_share,
                            .see_through = stats.see_through,
                            .misfit = stats.misfit,
                            .lost_bound = stats.lost_bound,
                            .places = stats.places,
                            .held = stats.held,
                            .switched = stats.switched,
                            .refined = filter.estimate().refined.pose,
                            .odometry = odometry});
}

void count_outcome(ReplayResult& result, const UpdateStats& stats) {
  ++result.outcomes[static_cast<std::size_t>(stats.outcome)];
  const bool unusual = stats.outcome != UpdateOutcome::kUpdated &&
                       stats.outcome != UpdateOutcome::kInitialized &&
                       stats.outcome != UpdateOutcome::kNotMoved;
  if (unusual && result.first_unusual_reason.empty()) result.first_unusual_reason = stats.reason;
}

std::vector<Pose2> particle_poses(const Localizer& filter) {
  const ConstParticleView view = filter.particles();
  std::vector<Pose2> poses(view.size());
  for (std::size_t i = 0; i < view.size(); ++i) poses[i] = view.pose(i);
  return poses;
}

// Runs every frame of the log through the filter (initialized on the first frame).
void run_frames(ReplayResult& result, Localizer& filter, logs::ScanSource& source,
                const ReplayOptions& options,
                const std::vector<logs::StampedPose>& sorted_reference) {
  while (true) {
    // The reader's share of the loop (reading, decompressing, decoding, tf): report.json read_s.
    const auto read_start = Clock::now();
    std::optional<logs::ScanFrame> frame = source.next();
    result.read_s += std::chrono::duration<double>(Clock::now() - read_start).count();
    if (!frame) break;
    if (result.scans == 0) {
      result.first_stamp = frame->stamp;
      result.laser_range_max = frame->scan.range_max;
      result.global_start = initialize(filter, options, sorted_reference, frame->stamp);
    }
    ++result.scans;
    filter.update(frame->odometry, frame->scan);
    count_outcome(result, filter.last_update());
    if (filter.last_update().ran()) {
      record_update(result, filter, frame->stamp, frame->odometry);
      if (options.on_update) options.on_update(filter, *frame);
    }
    if (options.progress) options.progress(result.scans);
  }
}

// A reference of the same log has a pose at nearly every update's stamp (every shared log: all of
// them); CARMEN stamps count from each log's start, so another log's reference still overlaps the
// run and matches a few updates by chance (Intel against the dev logs' references: 5-28 of 902).
// Scoring those few would print a meaningless ATE, so fewer matches than half the updates is an
// error with the numbers.
void check_reference_matches(const ReplayOptions& options, const ReplayResult& result,
                             const std::vector<logs::StampedPose>& sorted_reference) {
  const std::size_t updates = result.trajectory.size();
  const std::size_t matched = result.errors->matched;
  if (updates == 0 || 2 * matched >= updates) return;
  std::ostringstream problem;
  problem << std::fixed << std::setprecision(2) << "matches " << matched << " of the " << updates
          << " updates of " << options.log.string() << " within "
          << options.metrics.match_tolerance_s << " s (fewer than half; a log's own reference "
          << "matches nearly all): the log's updates span " << result.trajectory.front().stamp
          << " to " << result.trajectory.back().stamp << " s, the reference's poses "
          << sorted_reference.front().stamp << " to " << sorted_reference.back().stamp
          << " s: is it the reference of another log?";
  throw InputError(options.reference.string(), "", problem.str());
}

KidnapRecovery kidnap_recovery(const ReplayResult& result, const ReplayOptions& options,
                               const std::vector<logs::StampedPose>& sorted_reference) {
  KidnapRecovery k;
  k.at = *options.kidnapped_at;
  k.within_m = options.recovered_within_m;
  k.hold = options.recovered_hold;
  for (const logs::StampedPose& e : result.trajectory) k.updates_after += e.stamp >= k.at ? 1U : 0U;
  k.recovered_after = recovery_updates(result.trajectory, sorted_reference, k.at, k.within_m,
                                       k.hold, options.metrics.match_tolerance_s);
  return k;
}

}  // namespace

ReplayResult run_replay(const ReplayOptions& options) {
  ReplayResult result{load_map(options.map), options.config};
  if (!options.reference.empty()) result.reference = logs::read_tum(options.reference);
  const std::vector<logs::StampedPose> sorted_reference = logs::sort_by_stamp(result.reference);
  auto source = logs::open_scan_log(options.log, options.reader);
  Localizer filter(result.grid, options.config);  // shares the map: no copy
  result.threads = filter.threads();
  result.global_set = filter.global_set();
  result.beam_casting = filter.beam_casting();
  const RangeTable* table = filter.range_table();
  if (table) {
    result.range_table = summarize_range_table(
        result.map(), *table, {.unknown_blocks = options.config.unknown_cells_block_rays});
  }
  const auto start = Clock::now();
  run_frames(result, filter, *source, options, sorted_reference);
  result.wall_s = std::chrono::duration<double>(Clock::now() - start).count();

  result.reader = source->stats();
  result.laser_range_max_source = source->range_max_source();
  result.stamp_source = source->stamp_source();
  result.final_particles = particle_poses(filter);
  if (!result.reference.empty()) {
    MetricOptions metrics = options.metrics;
    metrics.start_stamp = result.first_stamp;
    result.errors = compare_trajectories(result.trajectory, sorted_reference, metrics);
    check_reference_matches(options, result, sorted_reference);
    result.particle_errors =
        compare_trajectories(result.particle_trajectory, sorted_reference, metrics);
    std::vector<LocalizationState> states;
    states.reserve(result.updates.size());
    for (const UpdateRecord& u : result.updates) states.push_back(u.state);
    result.off_updates = count_off_updates(result.trajectory, states, sorted_reference, kOffUpdateM,
                                           metrics.match_tolerance_s);
    if (options.kidnapped_at) result.kidnap = kidnap_recovery(result, options, sorted_reference);
  }
  return result;
}

const char* outcome_name(UpdateOutcome outcome) noexcept {
  switch (outcome) {
    case UpdateOutcome::kUpdated:
      return "updated";
    case UpdateOutcome::kInitialized:
      return "initialized";
    case UpdateOutcome::kNotMoved:
      return "not_moved";
    case UpdateOutcome::kRejectedOdometry:
      return "rejected_odometry";
    case UpdateOutcome::kRejectedScan:
      return "rejected_scan";
    case UpdateOutcome::kUnexplainedScan:
      return "unexplained_scan";
  }
  return "unknown";
}

const char* model_name(LaserModel model) noexcept { return name_of(model); }

}  // namespace mote::replay
