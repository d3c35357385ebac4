// Re-localization: what the filter does once the localization state says it is lost
// (localization_state.hpp). It replaces augmented MCL's injection (Thrun et al., table 8.3) in
// mote's defaults: injection replaced particles update after update for as long as the scans
// fitted worse than their long-term average, KLD grew the set with every injected bin, and a
// hard stretch of data made each update cost a global initialization's for hundreds of updates
// while the filter was not lost at all.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "field_walker.hpp"
#include "localizer_impl.hpp"
#include "mote/engine/recovery.hpp"
#include "mote/engine/relocalization.hpp"
#include "mote/engine/resample.hpp"
#include "see_through.hpp"

namespace mote {
namespace {

// Share of the belief the particles already there keep: a hypothesis that still explains the
// scans (a false alarm, a crowd) then outweighs every fresh particle at a look-alike place by
// the ratio of the set sizes, and loses to the fresh particles only where the scans favour
// them.
constexpr double kKeptWeight = 0.5;
// Scans in a row that did not move the robot after which a lost filter (or one whose scan no
// longer fits its estimate) runs an update anyway: updates need motion (update_min_d,
// update_min_a), and a lost robot standing still would otherwise never re-localize.
constexpr std::uint64_t kStillScans = 10;
// Keys the resampling that shrinks the kept set apart from the update's own resampling (same
// seed and step): no filter runs 2^63 updates.
constexpr std::uint64_t kShrinkStream = std::uint64_t{1} << 63U;

}  // namespace

bool RelocalizationSchedule::after_update(LocalizationState state, bool focused) noexcept {
  const bool tracking = state == LocalizationState::kTracking;
  tracked_ = next(tracked_, tracking);
  focused_ = next(focused_, focused);
  lost_ = next(lost_, state == LocalizationState::kLost);
  settled_ = settled_ || tracking || focused_ >= kConvergedAfter;
  if (tracked_ >= kTrackedToForgive) {
    wait_ = kFirstAfter;
    trusted_ = true;
  }
  if (!settled_ || lost_ < wait_) return false;
  lost_ = 0;
  wait_ = std::min(2 * wait_, kLongestWait);
  local_ = trusted_;
  trusted_ = false;
  return true;
}

void Localizer::Impl::reset_relocalization(bool settled) {
  schedule.reset(settled);
  relocalize_due = false;
  relocalize_locally = false;
  still_scans = 0;
}

void Localizer::Impl::count_lost_updates() {
  still_scans = 0;
  const bool due = schedule.after_update(stats.state, focused);
  relocalize_due = due && config.relocalize_when_lost;
  relocalize_locally = relocalize_due && schedule.local();
}

std::size_t Localizer::Impl::local_count(double radius) const {
  // The global set's density (global_particles_per_bin) over the KLD bins of the disc and every
  // heading: a local search is a global one over the part of the map the robot can be in.
  const double xy_bins =
      std::numbers::pi * radius * radius / (config.kld_bin_xy * config.kld_bin_xy);
  const double theta_bins = std::ceil(2.0 * std::numbers::pi / config.kld_bin_theta);
  if (config.global_particles_per_bin <= 0.0) return global_count();  // max_particles, as global
  const double wanted = std::ceil(config.global_particles_per_bin * xy_bins * theta_bins);
  return static_cast<std::size_t>(std::clamp(wanted, static_cast<double>(config.min_particles),
                                             static_cast<double>(global_count())));
}

bool Localizer::Impl::still_update_due(const LaserScan& scan) {
  // Only where a re-localization could follow: a global search that has not settled runs on
  // motion alone, as updates without it would weigh the same scan again and again.
  if (!config.relocalize_when_lost || !schedule.settled()) {
    still_scans = 0;
    return false;
  }
  if (++still_scans < kStillScans) return false;
  still_scans = 0;
  if (monitor.state() == LocalizationState::kLost) return true;
  // A robot carried off while standing still: no update has run since, so the state cannot
  // know. One look at the scan from the last refined pose (no refinement) tells whether it
  // still fits there, by the misfit the state smooths (see-through plus missed share) for this
  // scan alone: the missed share alone sat at the bound (0.58-0.60 where the bound is 0.6, with
  // 0.22-0.36 of the readings through walls), so the lost robot ran an update only now and
  // then and the smoothed misfit never reached it.
  select_endpoints(scan);
  const Pose2& at = estimate.refined.pose;
  const FieldWalker walk(map, field->signed_field);
  const double misfit = see_through_share(beams, at, walk, 2.0 * config.sigma_hit) +
                        (1.0 - matcher->hit_share(endpoints, at));
  // lost_misfit, not the learned bound: that is a limit on the smoothed misfit, and one scan of
  // a robot carried off read 0.58-0.60 (a scan at the glass of a learned map costs an update).
  return misfit > config.lost_misfit;  // false for NaN: no reading with an endpoint
}

void Localizer::Impl::maybe_relocalize() {
  if (!relocalize_due) return;
  relocalize_due = false;
  // The kept set and the global set share max_particles, the store's reserved capacity: a
  // re-localization neither reallocates mid-update nor exceeds the bound. When both do not fit,
  // the kept set is resampled down to what the global set leaves, but to no fewer than an
  // eighth of max_particles: it holds a hypothesis or a few (the weight it keeps, kKeptWeight,
  // does not depend on its count), where the global set must cover the whole map.
  const auto max_n = static_cast<std::size_t>(config.max_particles);
  // Local: within one scan range of the reported pose (held or refined), every heading. Odometry
  // that missed a turn or slid along a corridor leaves the robot there, and a global set would
  // offer every look-alike place of the building instead.
  const double radius = scan_range;
  const bool local = relocalize_locally && radius > 0.0 && is_finite(estimate.refined.pose);
  std::size_t fresh = std::min(local ? local_count(radius) : global_count(), max_n);
  std::size_t kept = store.size();
  if (kept + fresh > max_n) {
    kept = std::min(kept, std::max(max_n - fresh, (max_n + 7) / 8));
    fresh = max_n - kept;
    resample_systematic(store, kept, config.seed, step | kShrinkStream, config.grain);
  }
  const std::size_t before = store.size();
  if (local) {
    append_around(store, fresh, kKeptWeight, estimate.refined.pose, radius, config.seed, step,
                  config.grain);
  } else {
    append_uniform(store, fresh, kKeptWeight, map, config.seed, step, config.grain);
  }
  stats.relocalized = store.size() - before;
  stats.relocalized_locally = local && stats.relocalized > 0;
  monitor.reset_after_relocalization();
}

}  // namespace mote
