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
  if (smoothed_ > config_.lost_misfit) {
    state_ = LocalizationState::kLost;
  } else if (one_place && settling_ == 0) {
    state_ = LocalizationState::kTracking;
  } else {
    state_ = LocalizationState::kUncertain;
  }
  return state_;
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
