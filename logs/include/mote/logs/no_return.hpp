#pragma once
/// \file
/// The laser's "no return" reading inferred from the scans of a log. CARMEN FLASER/RLASER lines
/// do not record the maximum range, and lasers differ: a SICK LMS writes 81.83 m (8183 cm) when
/// a beam sees nothing, other lasers about 50 m. The code shows in the data as one exact value at
/// the top of many scans, since every beam without a return reads it.

#include <cstddef>
#include <map>
#include <span>
#include <string>

#include "mote/core/pose.hpp"

namespace mote::logs {

/// What NoReturnEstimator found.
struct NoReturnRange {
  float range_max = 0.0F;        ///< m, readings at or above it are "no return"
  bool repeated = false;         ///< true: a repeated top value (the code); false: the fallback
  std::size_t scans_at_max = 0;  ///< counted scans whose largest reading is range_max
  std::size_t scans = 0;         ///< scans counted

  /// One line for reports, e.g. "inferred: largest reading of 122 of the first 200 scans".
  [[nodiscard]] std::string describe() const;
};

/// Infers the no-return value from the first scans of a log.
///
/// Rule. Count a scan only when the odometry moved since the last counted one: a robot standing
/// still repeats its readings, a far maximum included, and would fake a code. For each counted
/// scan take its largest reading. The no-return value is the largest such maximum v that
///  - tops at least max(2, 1 %) of the counted scans: real far readings are sparse and noisy at
///    centimetre resolution, so the same exact top value in two scans taken at different poses
///    is a code, not a wall (on Wean Hall the code tops only 3 of the first 200 moving scans, so
///    the bar must stay low), and
///  - is topped by at most a quarter as many scans as it tops itself: a rare larger value (a
///    second error code such as SICK's 81.91 m "dazzled", or a glint) does not hide the code;
///    it still reads as no return since it is above range_max.
/// When no value qualifies the laser never failed to return in these scans: range_max is the
/// largest reading plus 1 %, so every reading seen stays a valid return. Misreading a real top
/// value as the code (two moving scans with the same far maximum, nothing larger) costs only
/// the readings at exactly that value, which become no-return; missing a real code would turn
/// every no-return into an obstacle at range_max, the failure this guards against.
class NoReturnEstimator {
 public:
  /// Counts one scan's readings (m; non-finite and non-positive ones ignored) taken at `odometry`.
  void add(std::span<const float> ranges, const Pose2& odometry);
  /// Scans counted so far.
  [[nodiscard]] std::size_t scans() const noexcept { return scans_; }
  /// The inferred value; range_max = 0 when no reading was counted.
  [[nodiscard]] NoReturnRange estimate() const;

 private:
  std::map<float, std::size_t> scans_topped_by_;  // largest reading -> scans
  std::size_t scans_ = 0;
  Pose2 last_odometry_;
  bool any_ = false;
};

}  // namespace mote::logs
