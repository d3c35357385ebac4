#pragma once
/// \file
/// Which place the filter reports while a new hypothesis challenges the one it has been
/// tracking: the reported pose moves to another place only once the scans have favoured that
/// place, scan after scan, while the robot travelled far enough to see it anew; until then it
/// stays on the tracked place, carried by the odometry and matched to each scan, and the state
/// is `uncertain`.
///
/// Why: a re-localization (or a look-alike place in a global search) can hand the heaviest
/// cluster to a place that one scan fitted better, where the tracked place saw through the map
/// for a few scans (an open door, glass); reporting it moved the pose tens of metres for a few
/// updates, and a planner acts on such a jump at once. The test is sequential: the readings
/// that hit the map at one place but not at the other are summed over the scans since the
/// challenge began, and the challenger takes over once McNemar's test on the sums favours it
/// beyond chance and the robot has travelled one scan range (HypothesisHold::after_scan). Two
/// places the scans cannot tell apart (a symmetric building, a corridor) have no discordant
/// readings, or as many each way, and never swap the reported pose.

#include <cstddef>

#include "mote/core/pose.hpp"

namespace mote {

/// Readings that hit the map (end within the matcher's scale of an obstacle's surface) from
/// one pose but not the other: the discordant pairs of McNemar's test.
struct HitDifference {
  std::size_t only_challenger = 0;
  std::size_t only_held = 0;
};

/// The sequential test between the held place and a challenger.
class HypothesisHold {
 public:
  /// The one-sided significance of a hand-over, over the whole challenge however long it runs.
  static constexpr double kAlpha = 0.001;
  /// One-sided z of a single look at 0.001 (keep_places' test of one scan).
  static constexpr double kZ = 3.09;
  /// Scans a challenger needs at least, however strong one scan's evidence.
  static constexpr int kMinScans = 2;

  /// Whether b is a different place from a at the scale of a scan of mean range `range` (m):
  /// moving from a to b shifts a typical endpoint (position offset plus heading offset times
  /// the range) by more than the range itself, so the two scans would barely overlap.
  [[nodiscard]] static bool other_place(const Pose2& a, const Pose2& b, double range) noexcept;

  /// McNemar's statistic (b - c) / sqrt((b + c) k) on discordant readings summed over scans,
  /// their count divided by k = `correlation` (the filter's running estimate of n over the
  /// effective number of independent readings in a scan, ScanMatch::correlation; values
  /// below 1 read as 1); 0 when no reading is discordant.
  [[nodiscard]] static double z(const HitDifference& d, double correlation) noexcept;

  /// Starts a challenge: no evidence, no travel.
  void challenge() noexcept {
    *this = HypothesisHold{};
    active_ = true;
  }
  /// Ends the challenge (the held place is the best hypothesis again, or the challenger won).
  void end() noexcept { *this = HypothesisHold{}; }
  /// The z the sums must pass at the n-th scan of a challenge: the one-sided quantile at
  /// kAlpha / (n (n + 1)). The test looks after every scan, and these levels sum to kAlpha over
  /// all looks (Bonferroni over a series that sums to 1), so a challenge between two places the
  /// scans cannot tell apart hands over with probability under kAlpha however long it runs; at
  /// one level for every look it handed over 0.75 % of 50-scan challenges and 2.6 % of
  /// 1000-scan ones (a simulation with 10 discordant readings a scan split evenly). 3.59 at the
  /// second scan, 4.29 at the tenth, 5.20 at the hundredth: a real challenger's z grows as the
  /// square root of the scans, faster.
  [[nodiscard]] static double boundary(int n);
  /// Adds one scan's discordant readings and the robot's motion since the previous scan (m,
  /// plus rad times `range`); true when the challenger has won: z() of the sums above
  /// boundary(n) after kMinScans scans or more and a travel of at least `range` (a view the
  /// challenger had not fitted yet). Where z() falls below -boundary(n) the held place has
  /// explained the scans better, and the evidence starts over.
  bool after_scan(const HitDifference& d, double correlation, double travelled, double range);

  [[nodiscard]] bool active() const noexcept { return active_; }
  [[nodiscard]] int scans() const noexcept { return scans_; }
  [[nodiscard]] const HitDifference& evidence() const noexcept { return sum_; }

 private:
  HitDifference sum_;
  int scans_ = 0;
  double travelled_ = 0.0;
  bool active_ = false;
};

}  // namespace mote
