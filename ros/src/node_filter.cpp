// The filter thread: swaps in a prepared map, applies start poses and requests, runs the update
// on the newest scan and publishes what it found.
#include <algorithm>
#include <cmath>
#include <utility>

#include "node_impl.hpp"
#include "pose_file.hpp"

namespace mote::ros {
namespace {

// The latency percentiles cover this many of the last processed scans.
constexpr std::size_t kLatencyWindow = 100000;

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

}  // namespace

std::uint64_t Node::Impl::counts_maps() const {
  const std::lock_guard lock(mutex);
  return counts.maps;
}

std::optional<StartPose> Node::Impl::start_pose_for_new_map() const {
  {
    const std::lock_guard lock(mutex);
    // A map that replaces another keeps a belief that knew where it was.
    if (counts.maps > 0 && counts.state == LocalizationState::kTracking &&
        !options.always_reset_initial_pose) {
      return StartPose{counts.pose, options.initial_covariance, kLastPose};
    }
    if (counts.maps > 0) return std::nullopt;
  }
  if (options.initial_pose) {
    return StartPose{*options.initial_pose, options.initial_covariance, "the initial pose"};
  }
  if (!options.pose_file.empty()) {
    if (const std::optional<Pose2> saved = read_pose_file(options.pose_file, warnings)) {
      return StartPose{*saved, options.initial_covariance,
                       "the pose saved in " + options.pose_file.string()};
    }
  }
  return std::nullopt;
}

void Node::Impl::filter_loop() {
  for (;;) {
    std::optional<ReadyScan> scan;
    std::optional<PreparedFilter> prepared;
    std::optional<StartPose> start;
    bool global = false;
    bool nomotion = false;
    {
      std::unique_lock lock(mutex);
      wake_filter.wait(lock, [&] {
        return stopping || pending_scan || pending_filter || pending_start || global_requested;
      });
      if (stopping) return;
      prepared = std::exchange(pending_filter, std::nullopt);
      start = std::exchange(pending_start, std::nullopt);
      global = std::exchange(global_requested, false);
      nomotion = std::exchange(nomotion_requested, false);
      scan = std::exchange(pending_scan, std::nullopt);
    }
    if (prepared) swap_in(std::move(*prepared));
    if (filter && start) start_at(*start);
    if (filter && global) {
      filter->initialize_global();
      warnings.notice("re-initialized over the map's free space (" +
                      std::to_string(filter->particles().size()) + " particles)");
    }
    if (filter && nomotion) filter->force_next_update();
    if (!filter && start) deferred_start = start;  // applied when the map arrives
    if (!filter && (global || nomotion)) {
      warnings.warn("no map", "no map yet: the request is ignored");
    }
    if (scan) process(*scan);
  }
}

void Node::Impl::swap_in(PreparedFilter prepared) {
  if (prepared.at_last_pose) start_at_last_pose(*prepared.filter);
  filter = std::move(prepared.filter);
  have_map_to_odom = false;
  if (deferred_start) start_at(*std::exchange(deferred_start, std::nullopt));
}

void Node::Impl::start_at_last_pose(Localizer& next) const {
  // Where the robot is now, not where it was when the map arrived: preparing a big map takes
  // seconds, and the old filter kept tracking meanwhile.
  LocalizationState state = LocalizationState::kLost;
  Pose2 pose;
  {
    const std::lock_guard lock(mutex);
    state = counts.state;
    pose = counts.pose;
  }
  if (state == LocalizationState::kTracking) {
    next.initialize(pose, options.initial_covariance);
    warnings.notice("new map: filter started at the last pose, x " + std::to_string(pose.x) +
                    " y " + std::to_string(pose.y) + " yaw " + std::to_string(pose.theta));
    return;
  }
  next.initialize_global();
  warnings.notice(
      "new map: the filter stopped tracking while the map was prepared, started "
      "globally (" +
      std::to_string(next.particles().size()) + " particles)");
  warn_if_global_set_capped(next);
}

void Node::Impl::start_at(const StartPose& start) {
  filter->initialize(start.pose, start.covariance);
  have_map_to_odom = false;
  warnings.notice("initialized at " + start.source + ": x " + std::to_string(start.pose.x) + " y " +
                  std::to_string(start.pose.y) + " yaw " + std::to_string(start.pose.theta));
}

void Node::Impl::process(const ReadyScan& scan) {
  if (!filter) {
    const std::lock_guard lock(mutex);
    ++counts.dropped_no_map;
    return;
  }
  const logs::ScanFrame& f = scan.frame;
  bool ran = false;
  try {
    ran = filter->update(f.odometry, f.scan);
  } catch (const std::exception& e) {
    warnings.warn("update failed", std::string("update failed, filter kept: ") + e.what());
  }
  const UpdateStats& u = filter->last_update();
  if (u.outcome == UpdateOutcome::kRejectedScan) {
    warnings.warn("scan refused", "scan at " + std::to_string(f.stamp) + " s refused: " + u.reason);
  }
  if (ran) {
    // map -> odom = (map -> base) * (odom -> base)^-1 at the scan's stamp (REP 105).
    map_to_odom = compose(filter->estimate().refined.pose, inverse(f.odometry));
    have_map_to_odom = true;
  }
  // The transform first: it is what nav2 waits for; the cloud can take milliseconds to encode.
  if (have_map_to_odom) publish_transform(f.stamp);
  record_latency(scan);
  if (ran) {
    publish_estimate(f.stamp);
    publish_state(f.stamp);
    maybe_save_pose(f.stamp);
  }
  if (ran && u.state != reported_state) {
    reported_state = u.state;
    warnings.notice("t " + std::to_string(f.stamp) + " s: " + name_of(u.state) + " (misfit " +
                    std::to_string(u.misfit) + " against " + std::to_string(u.lost_bound) + ", " +
                    std::to_string(u.particles) + " particles, " +
                    std::to_string(filter->estimate().clusters.size()) + " clusters)");
  }
  const std::lock_guard lock(mutex);
  ++counts.scans_processed;
  if (ran) {
    ++counts.updates;
    counts.state = u.state;
    counts.misfit = u.misfit;
    counts.pose = filter->estimate().refined.pose;
    counts.pose_stamp = f.stamp;
  }
}

void Node::Impl::record_latency(const ReadyScan& scan) {
  const double total = ms_since(scan.arrived);
  const double own = ms_since(scan.ready);
  const std::lock_guard lock(mutex);
  latencies_ms.push_back(total);
  processing_ms.push_back(own);
  if (latencies_ms.size() > kLatencyWindow) {
    latencies_ms.pop_front();
    processing_ms.pop_front();
  }
}

}  // namespace mote::ros
