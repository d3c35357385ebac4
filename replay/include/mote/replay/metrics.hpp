#pragma once
/// \file
/// Accuracy and timing figures of a localization run: absolute trajectory error against a
/// reference in the map frame (no alignment, since MCL localizes in the map's own frame), the
/// time from which the filter stays converged, and percentiles of per-update times.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "mote/engine/localization_state.hpp"
#include "mote/logs/tum.hpp"

namespace mote::replay {

/// How estimates are paired with reference poses and what "converged" means.
struct MetricOptions {
  double match_tolerance_s =
      logs::kReferenceMatchTolerance;  ///< s, largest stamp gap to a reference
  double converged_m = 0.5;            ///< m, position error under which a pose counts as converged
  double converged_deg = 10.0;         ///< degrees, heading error bound for converged
  /// Matched estimates per window of the convergence rule (TrajectoryErrors::converged_at_s).
  std::size_t converged_window = 20;
  /// Estimates outside the bounds a window may hold and still count as converged: 1 in 20 lets
  /// isolated outliers (one bad scan match) pass, a stretch of being lost does not.
  std::size_t converged_outliers = 1;
  double start_stamp = 0.0;  ///< s, time origin of converged_at_s (the first scan)
};

/// Errors of an estimated trajectory against a reference.
struct TrajectoryErrors {
  std::size_t matched = 0;        ///< estimates that found a reference pose within tolerance
  double ate_rmse_m = 0.0;        ///< m, RMS of position errors over matched poses (NaN if 0)
  double heading_rmse_deg = 0.0;  ///< degrees, RMS of wrapped heading errors (NaN if 0)
  double max_error_m = 0.0;       ///< m, largest position error
  /// s after start_stamp of the first time from which the filter stays converged except for
  /// isolated outliers: the first matched estimate k within both bounds such that every window
  /// of converged_window consecutive matched estimates starting at or after k (shorter at the
  /// end of the run) holds at most converged_outliers estimates outside them. With the defaults
  /// (1 in 20, i.e. 95 %) a single bad pose does not reset convergence, two within 20 updates
  /// do, and so does a lost stretch; a run whose last two matched estimates are off never
  /// converged. nullopt when no such k exists.
  std::optional<double> converged_at_s;
  /// The same figures over the matched estimates from converged_at_s on (nullopt when the run
  /// never converged): global localization's first updates, spread over the building, would
  /// otherwise dominate a run's ATE.
  struct AfterConvergence {
    std::size_t matched = 0;
    double ate_rmse_m = 0.0;
    double heading_rmse_deg = 0.0;
    double max_error_m = 0.0;
  };
  std::optional<AfterConvergence> after_convergence;
};

/// Compares `estimate` (in run order) with `reference` (any order).
[[nodiscard]] TrajectoryErrors compare_trajectories(std::span<const logs::StampedPose> estimate,
                                                    std::span<const logs::StampedPose> reference,
                                                    const MetricOptions& options = {});

/// m: an update whose reported pose lies farther than this from the reference pose is off. The
/// issue-47 target (no update this far off while the state says tracking) and the bound the
/// accuracy table calls a lost run (scripts/accuracy-table); report.json's updates_over_1m.
inline constexpr double kOffUpdateM = 1.0;

/// The updates whose estimate was off, and whether the filter told the user.
struct OffUpdates {
  std::size_t off = 0;      ///< matched estimates more than the bound from the reference
  std::size_t flagged = 0;  ///< of those, the ones whose state was not `tracking`
  /// Off while the state said `tracking`: wrong and not flagged, what a planner would act on.
  [[nodiscard]] std::size_t tracking() const noexcept { return off - flagged; }
};

/// Counts the estimates (in run order, `states` one per estimate) farther than `bound_m` from the
/// reference pose nearest in time within `tolerance` s, as compare_trajectories pairs them (so
/// `off` is 0 exactly when its max_error_m is at most `bound_m`), and those among them whose
/// state was `uncertain` or `lost`. Unmatched estimates do not count; an estimate without a
/// state counts as `tracking`. `sorted_reference` must be sorted by stamp (sort_by_stamp).
[[nodiscard]] OffUpdates count_off_updates(std::span<const logs::StampedPose> estimate,
                                           std::span<const LocalizationState> states,
                                           std::span<const logs::StampedPose> sorted_reference,
                                           double bound_m = kOffUpdateM,
                                           double tolerance = logs::kReferenceMatchTolerance);

/// Filter updates it took to recover from a kidnapping at `kidnap_stamp` (s): among the estimates
/// stamped at or after it (in run order), the number that come before the first of `hold`
/// consecutive matched estimates all within `within_m` m of the reference, i.e. how many updates
/// the filter spent lost (0 = it never lost track). Estimates without a reference pose within
/// `tolerance` s neither count toward nor break the run. nullopt when no such run exists (never
/// recovered, or recovered too close to the end of the log to hold). `sorted_reference` must be
/// sorted by stamp (sort_by_stamp).
[[nodiscard]] std::optional<std::size_t> recovery_updates(
    std::span<const logs::StampedPose> estimate,
    std::span<const logs::StampedPose> sorted_reference, double kidnap_stamp, double within_m = 0.3,
    std::size_t hold = 20, double tolerance = 0.05);

/// Mean and order statistics of a sample (e.g. update times, ms). All zero for an empty sample.
struct Percentiles {
  double mean = 0.0;
  double p50 = 0.0;  ///< median (nearest rank)
  double p99 = 0.0;  ///< 99th percentile (nearest rank)
  double max = 0.0;
};

/// Percentiles of `values` by the nearest-rank method.
[[nodiscard]] Percentiles summarize(std::vector<double> values);

}  // namespace mote::replay
