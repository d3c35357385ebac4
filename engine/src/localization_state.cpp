#include "mote/engine/localization_state.hpp"

#include <algorithm>
#include <cmath>

namespace mote {

const char* name_of(LocalizationState state) noexcept {
  switch (state) {
    case LocalizationState::kTracking:
      return "tracking";
    case LocalizationState::kUncertain:
      return "uncertain";
    case LocalizationState::kLost:
      return "lost";
  }
  return "unknown";
}

LocalizationState LocalizationMonitor::update(double see_through, double hit_share,
                                              bool one_place) noexcept {
  const double misfit = see_through + (1.0 - hit_share);
  if (!std::isfinite(misfit)) return state_;
  smoothed_ = started_ ? smoothed_ + config_.smoothing * (misfit - smoothed_) : misfit;
  started_ = true;
  if (settling_ > 0) --settling_;
  if (smoothed_ > lost_bound()) {
    state_ = LocalizationState::kLost;
  } else if (one_place && settling_ == 0) {
    state_ = LocalizationState::kTracking;
  } else {
    state_ = LocalizationState::kUncertain;
  }
  learn();
  return state_;
}

void LocalizationMonitor::learn() noexcept {
  // A point once the average spans only tracked scans (its window in a row), and only below
  // lost_misfit: points the learned bound itself let through would let it creep up on a wrong
  // map, whose scans fit now and then.
  // Counted to one past the window only (a run of years would overflow an int).
  tracking_run_ =
      state_ == LocalizationState::kTracking ? std::min(tracking_run_ + 1, window() + 1) : 0;
  if (tracking_run_ <= window() || !(smoothed_ <= config_.lost_misfit)) return;
  chart_n_ += 1.0;
  const double delta = smoothed_ - chart_mean_;
  chart_mean_ += delta / chart_n_;
  chart_m2_ += delta * (smoothed_ - chart_mean_);
}

double LocalizationMonitor::lost_bound() const noexcept {
  const double floor = config_.lost_misfit;
  if (!config_.learn || chart_n_ < config_.chart_min_updates || chart_n_ < 2.0) return floor;
  const double sd = std::sqrt(chart_m2_ / (chart_n_ - 1.0));
  return std::clamp(chart_mean_ + config_.chart_sigmas * sd, floor, config_.chart_ceiling * floor);
}

int LocalizationMonitor::window() const noexcept {
  constexpr double kLongestWindow = 1000.0;  // a smoothing of 0 (never averaging) is no window
  return config_.smoothing > 0.0
             ? static_cast<int>(std::min(std::ceil(1.0 / config_.smoothing), kLongestWindow))
             : 0;
}

void LocalizationMonitor::reset_after_relocalization() noexcept {
  reset();
  // The average's window, about 1 / smoothing updates: one scan that fits a fresh place is the
  // chance a global set offers at every look-alike place, not a place that has held.
  settling_ = window();
}

}  // namespace mote
