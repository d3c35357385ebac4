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
  // Learned from scans taken while the filter tracks one place: the previous verdict, as this
  // scan's is still to be made.
  if (state_ == LocalizationState::kTracking && one_place) baseline_.add(misfit);
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
  return state_;
}

void MisfitBaseline::add(double misfit) noexcept {
  // Welford's running mean and variance until the window is full, then exponential forgetting
  // at kRate (West 1979's weighted update), so the baseline follows a map that ages.
  ++n_;
  const double rate = std::max(kRate, 1.0 / static_cast<double>(n_));
  const double d = misfit - mean_;
  mean_ += rate * d;
  variance_ = (1.0 - rate) * (variance_ + rate * d * d);
}

double MisfitBaseline::bound() const noexcept {
  if (n_ < kMinSamples) return 0.0;
  return mean_ + kZ * std::sqrt(std::max(0.0, variance_));
}

double LocalizationMonitor::lost_bound() const noexcept {
  return std::max(config_.lost_misfit, baseline_.bound());
}

void LocalizationMonitor::reset_after_relocalization() noexcept {
  reset();
  // The average's window, about 1 / smoothing updates: one scan that fits a fresh place is the
  // chance a global set offers at every look-alike place, not a place that has held.
  constexpr double kLongestSettling = 1000.0;  // a smoothing of 0 (never averaging) is no window
  settling_ = config_.smoothing > 0.0
                  ? static_cast<int>(std::min(std::ceil(1.0 / config_.smoothing), kLongestSettling))
                  : 0;
}

}  // namespace mote
