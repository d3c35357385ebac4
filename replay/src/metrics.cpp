// Trajectory error metrics (ATE in the map frame, heading RMSE, convergence) and percentiles.
#include "mote/replay/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "mote/core/pose.hpp"

namespace mote::replay {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

struct PoseError {
  double stamp = 0.0;
  double position_m = 0.0;
  double heading_deg = 0.0;
};

// Nearest-rank percentile of a sorted sample: the smallest value with at least p of the sample
// at or below it.
double nearest_rank(const std::vector<double>& sorted, double p) {
  const auto n = static_cast<double>(sorted.size());
  const auto rank = static_cast<std::size_t>(std::max(1.0, std::ceil(p * n)));
  return sorted[std::min(rank, sorted.size()) - 1];
}

std::vector<PoseError> pose_errors(std::span<const logs::StampedPose> estimate,
                                   std::span<const logs::StampedPose> reference, double tolerance) {
  std::vector<PoseError> errors;
  errors.reserve(estimate.size());
  for (const logs::StampedPose& e : estimate) {
    const auto ref = logs::match_reference(reference, e.stamp, tolerance);
    if (!ref) continue;
    const double dx = e.pose.x - ref->pose.x;
    const double dy = e.pose.y - ref->pose.y;
    const double dtheta = wrap_angle(e.pose.theta - ref->pose.theta);
    errors.push_back({e.stamp, std::hypot(dx, dy), std::abs(dtheta) * kRadToDeg});
  }
  return errors;
}

bool within(const PoseError& e, const MetricOptions& options) {
  return e.position_m < options.converged_m && e.heading_deg < options.converged_deg;
}

// The convergence rule of TrajectoryErrors::converged_at_s. Scanning from the end with a sliding
// count of outliers, the last window start j holding too many fixes the earliest admissible k
// at j + 1 (windows starting before k do not matter); k is the first estimate within the bounds
// from there.
std::optional<std::size_t> converged_from(const std::vector<PoseError>& errors,
                                          const MetricOptions& options) {
  const std::size_t n = errors.size();
  const std::size_t window = std::max<std::size_t>(options.converged_window, 1);
  std::size_t earliest = 0;
  std::size_t outliers = 0;  // outside the bounds in [j, min(j + window, n))
  for (std::size_t j = n; j-- > 0;) {
    outliers += within(errors[j], options) ? 0U : 1U;
    if (j + window < n && !within(errors[j + window], options)) --outliers;
    if (outliers > options.converged_outliers) {
      earliest = j + 1;
      break;
    }
  }
  for (std::size_t k = earliest; k < n; ++k) {
    if (within(errors[k], options)) return k;
  }
  return std::nullopt;
}

// RMS position and heading errors and the largest position error of `errors` (not empty).
TrajectoryErrors::AfterConvergence rms_of(std::span<const PoseError> errors) {
  TrajectoryErrors::AfterConvergence out;
  double sum_p = 0.0;
  double sum_h = 0.0;
  for (const PoseError& e : errors) {
    sum_p += e.position_m * e.position_m;
    sum_h += e.heading_deg * e.heading_deg;
    out.max_error_m = std::max(out.max_error_m, e.position_m);
  }
  out.matched = errors.size();
  const auto n = static_cast<double>(errors.size());
  out.ate_rmse_m = std::sqrt(sum_p / n);
  out.heading_rmse_deg = std::sqrt(sum_h / n);
  return out;
}

}  // namespace

TrajectoryErrors compare_trajectories(std::span<const logs::StampedPose> estimate,
                                      std::span<const logs::StampedPose> reference,
                                      const MetricOptions& options) {
  const std::vector<logs::StampedPose> sorted = logs::sort_by_stamp(reference);
  const std::vector<PoseError> errors = pose_errors(estimate, sorted, options.match_tolerance_s);
  TrajectoryErrors out;
  out.matched = errors.size();
  if (errors.empty()) {
    out.ate_rmse_m = std::numeric_limits<double>::quiet_NaN();
    out.heading_rmse_deg = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  const TrajectoryErrors::AfterConvergence all = rms_of(errors);
  out.ate_rmse_m = all.ate_rmse_m;
  out.heading_rmse_deg = all.heading_rmse_deg;
  out.max_error_m = all.max_error_m;
  if (const auto from = converged_from(errors, options)) {
    out.converged_at_s = errors[*from].stamp - options.start_stamp;
    out.after_convergence =
        rms_of(std::span<const PoseError>(errors).subspan(static_cast<std::size_t>(*from)));
  }
  return out;
}

OffUpdates count_off_updates(std::span<const logs::StampedPose> estimate,
                             std::span<const LocalizationState> states,
                             std::span<const logs::StampedPose> sorted_reference, double bound_m,
                             double tolerance) {
  OffUpdates out;
  for (std::size_t k = 0; k < estimate.size(); ++k) {
    const logs::StampedPose& e = estimate[k];
    const auto ref = logs::match_reference(sorted_reference, e.stamp, tolerance);
    if (!ref || !(std::hypot(e.pose.x - ref->pose.x, e.pose.y - ref->pose.y) > bound_m)) continue;
    ++out.off;
    const bool tracking = k >= states.size() || states[k] == LocalizationState::kTracking;
    out.flagged += tracking ? 0U : 1U;
  }
  return out;
}

std::optional<std::size_t> recovery_updates(std::span<const logs::StampedPose> estimate,
                                            std::span<const logs::StampedPose> sorted_reference,
                                            double kidnap_stamp, double within_m, std::size_t hold,
                                            double tolerance) {
  std::size_t after = 0;      // estimates at or after the kidnapping so far
  std::size_t run_start = 0;  // index (among those) of the current run's first estimate
  std::size_t run = 0;        // matched estimates within the bound in the current run
  for (const logs::StampedPose& e : estimate) {
    if (e.stamp < kidnap_stamp) continue;
    const std::size_t index = after++;
    const auto ref = logs::match_reference(sorted_reference, e.stamp, tolerance);
    if (!ref) continue;
    if (std::hypot(e.pose.x - ref->pose.x, e.pose.y - ref->pose.y) > within_m) {
      run = 0;
      continue;
    }
    if (run++ == 0) run_start = index;
    if (run >= hold) return run_start;
  }
  return std::nullopt;
}

Percentiles summarize(std::vector<double> values) {
  Percentiles out;
  if (values.empty()) return out;
  std::sort(values.begin(), values.end());
  out.mean =
      std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  out.p50 = nearest_rank(values, 0.50);
  out.p99 = nearest_rank(values, 0.99);
  out.max = values.back();
  return out;
}

}  // namespace mote::replay
