// Trajectory metrics on hand-made trajectories: ATE, heading RMSE, matching, convergence.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "mote/replay/metrics.hpp"

namespace mote::replay {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::vector<logs::StampedPose> straight_line(std::size_t n, double dt) {
  std::vector<logs::StampedPose> out;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = 100.0 + static_cast<double>(k) * dt;
    out.push_back({t, {static_cast<double>(k) * 0.1, 0.0, 0.3}});
  }
  return out;
}

TEST(Metrics, IdenticalTrajectoriesHaveZeroError) {
  const auto ref = straight_line(50, 0.1);
  const TrajectoryErrors e = compare_trajectories(ref, ref);
  EXPECT_EQ(e.matched, 50U);
  EXPECT_DOUBLE_EQ(e.ate_rmse_m, 0.0);
  EXPECT_DOUBLE_EQ(e.heading_rmse_deg, 0.0);
  ASSERT_TRUE(e.converged_at_s.has_value());
}

TEST(Metrics, AteIsRootMeanSquareOfPositionErrors) {
  const auto ref = straight_line(4, 1.0);
  auto est = ref;
  // Offsets 3-4-5, 0, 1, 0 m: RMS = sqrt((25 + 0 + 1 + 0) / 4).
  est[0].pose.x += 3.0;
  est[0].pose.y += 4.0;
  est[2].pose.y -= 1.0;
  const TrajectoryErrors e = compare_trajectories(est, ref);
  EXPECT_NEAR(e.ate_rmse_m, std::sqrt(26.0 / 4.0), 1e-12);
  EXPECT_NEAR(e.max_error_m, 5.0, 1e-12);
}

TEST(Metrics, HeadingErrorIsWrappedAndInDegrees) {
  std::vector<logs::StampedPose> ref{{1.0, {0, 0, 179.0 * kDeg}}, {2.0, {0, 0, 0.0}}};
  std::vector<logs::StampedPose> est{{1.0, {0, 0, -179.0 * kDeg}}, {2.0, {0, 0, 4.0 * kDeg}}};
  // Errors 2 and 4 degrees (the first across the +-pi seam): RMS = sqrt((4 + 16) / 2).
  const TrajectoryErrors e = compare_trajectories(est, ref);
  EXPECT_NEAR(e.heading_rmse_deg, std::sqrt(10.0), 1e-9);
}

TEST(Metrics, MatchesNearestStampWithinTolerance) {
  const std::vector<logs::StampedPose> ref{{1.00, {1, 0, 0}}, {1.10, {2, 0, 0}}, {1.20, {3, 0, 0}}};
  EXPECT_DOUBLE_EQ(logs::match_reference(ref, 1.06, 0.05)->pose.x, 2.0);
  EXPECT_DOUBLE_EQ(logs::match_reference(ref, 1.04, 0.05)->pose.x, 1.0);
  EXPECT_DOUBLE_EQ(logs::match_reference(ref, 1.23, 0.05)->pose.x, 3.0);
  EXPECT_FALSE(logs::match_reference(ref, 1.30, 0.05).has_value());
  EXPECT_FALSE(logs::match_reference(ref, 0.90, 0.05).has_value());
  EXPECT_FALSE(logs::match_reference({}, 1.0, 0.05).has_value());
}

TEST(Metrics, UnsortedReferenceIsSortedBeforeMatching) {
  auto ref = straight_line(20, 0.5);
  std::swap(ref[3], ref[15]);
  const TrajectoryErrors e = compare_trajectories(straight_line(20, 0.5), ref);
  EXPECT_EQ(e.matched, 20U);
  EXPECT_DOUBLE_EQ(e.ate_rmse_m, 0.0);
}

TEST(Metrics, UnmatchedEstimatesAreSkippedAndNoMatchGivesNaN) {
  const auto ref = straight_line(10, 1.0);
  auto est = ref;
  est[4].stamp += 0.5;  // no reference within 0.05 s
  est[4].pose.x += 100.0;
  EXPECT_EQ(compare_trajectories(est, ref).matched, 9U);
  EXPECT_DOUBLE_EQ(compare_trajectories(est, ref).ate_rmse_m, 0.0);
  const TrajectoryErrors none = compare_trajectories(est, {});
  EXPECT_EQ(none.matched, 0U);
  EXPECT_TRUE(std::isnan(none.ate_rmse_m));
  EXPECT_FALSE(none.converged_at_s.has_value());
}

TEST(Metrics, ConvergedAtIsFirstTimeFromWhichErrorStaysSmall) {
  const auto ref = straight_line(60, 1.0);  // stamps 100 .. 159
  auto est = ref;
  for (std::size_t k = 0; k < 10; ++k) est[k].pose.x += 2.0;  // lost until stamp 109
  est[20].pose.y += 0.49;                                     // still inside 0.5 m
  MetricOptions options;
  options.start_stamp = 100.0;
  const TrajectoryErrors e = compare_trajectories(est, ref, options);
  ASSERT_TRUE(e.converged_at_s.has_value());
  EXPECT_DOUBLE_EQ(*e.converged_at_s, 10.0);
}

TEST(Metrics, IsolatedOutliersDoNotResetConvergence) {
  const auto ref = straight_line(60, 1.0);
  auto est = ref;
  for (std::size_t k = 0; k < 10; ++k) est[k].pose.x += 2.0;  // lost until stamp 109
  est[14].pose.theta += 15.0 * kDeg;                          // heading glitch at 114
  est[35].pose.x += 3.0;                                      // one bad match at 135
  est[59].pose.y += 0.6;                                      // and at the very end
  MetricOptions options;
  options.start_stamp = 100.0;
  EXPECT_DOUBLE_EQ(*compare_trajectories(est, ref, options).converged_at_s, 10.0);
  // Two outliers within 20 updates are not isolated: 135 and 145, then 145 and 159, so the
  // filter counts as converged after 145.
  est[45].pose.x += 3.0;
  EXPECT_DOUBLE_EQ(*compare_trajectories(est, ref, options).converged_at_s, 46.0);
}

TEST(Metrics, ALostStretchResetsConvergence) {
  const auto ref = straight_line(60, 1.0);
  auto est = ref;
  for (std::size_t k = 0; k < 5; ++k) est[k].pose.x += 2.0;
  for (std::size_t k = 30; k < 38; ++k) est[k].pose.x += 5.0;  // lost again 130 .. 137
  MetricOptions options;
  options.start_stamp = 100.0;
  EXPECT_DOUBLE_EQ(*compare_trajectories(est, ref, options).converged_at_s, 38.0);
}

TEST(Metrics, NeverConvergedWhenTheLastPosesAreOff) {
  const auto ref = straight_line(10, 1.0);
  auto est = ref;
  est[8].pose.x += 0.6;
  est[9].pose.x += 0.6;
  EXPECT_FALSE(compare_trajectories(est, ref).converged_at_s.has_value());
  auto lost = ref;
  for (logs::StampedPose& p : lost) p.pose.y += 1.0;
  EXPECT_FALSE(compare_trajectories(lost, ref).converged_at_s.has_value());
}

// Recovery after a kidnapping at stamp 110 (index 10 of a 1 s trajectory starting at 100).
std::vector<logs::StampedPose> lost_between(std::size_t from, std::size_t to) {
  auto est = straight_line(60, 1.0);
  for (std::size_t k = from; k < to; ++k) est[k].pose.x += 27.0;
  return est;
}

TEST(Metrics, RecoveryCountsUpdatesSpentLost) {
  const auto ref = straight_line(60, 1.0);
  // Lost for the 7 updates 110..116, back from 117 on.
  EXPECT_EQ(recovery_updates(lost_between(10, 17), ref, 110.0), std::optional<std::size_t>(7));
  // Never lost.
  EXPECT_EQ(recovery_updates(ref, ref, 110.0), std::optional<std::size_t>(0));
  // Errors before the kidnapping do not count.
  EXPECT_EQ(recovery_updates(lost_between(0, 17), ref, 110.0), std::optional<std::size_t>(7));
}

TEST(Metrics, RecoveryNeedsTheHold) {
  const auto ref = straight_line(60, 1.0);
  EXPECT_FALSE(recovery_updates(lost_between(10, 60), ref, 110.0).has_value());  // never
  // Back at 150 but only 10 updates remain: not held for 20.
  EXPECT_FALSE(recovery_updates(lost_between(10, 50), ref, 110.0).has_value());
  EXPECT_EQ(recovery_updates(lost_between(10, 50), ref, 110.0, 0.3, 10),
            std::optional<std::size_t>(40));
}

TEST(Metrics, RecoveryThatLeavesAndComesBackCountsFromTheLastReturn) {
  const auto ref = straight_line(60, 1.0);
  auto est = lost_between(10, 15);                              // back at 115 ...
  for (std::size_t k = 25; k < 28; ++k) est[k].pose.y += 0.31;  // ... off again 125..127
  // The run from 115 holds only 10 updates, so the recovery is the run from 128: 18 updates.
  EXPECT_EQ(recovery_updates(est, ref, 110.0), std::optional<std::size_t>(18));
  // Unmatched estimates (no reference within 0.05 s) neither break a run nor count toward it.
  est = lost_between(10, 15);
  est[20].stamp += 0.5;
  est[20].pose.x += 9.0;
  EXPECT_EQ(recovery_updates(est, ref, 110.0), std::optional<std::size_t>(5));
}

// Off updates on a 1 s trajectory: which are more than 1 m off and which of them were flagged.
TEST(Metrics, OffUpdatesCountThoseMoreThanABoundOffAndTheFlaggedAmongThem) {
  using enum LocalizationState;
  const auto ref = straight_line(12, 1.0);
  auto est = ref;
  std::vector<LocalizationState> states(est.size(), kTracking);
  est[1].pose.y += 1.0;   // exactly at the bound: not off
  est[3].pose.y -= 1.01;  // off while tracking
  est[4].pose.x += 5.0;   // off, uncertain
  states[4] = kUncertain;
  est[5].pose.x -= 30.0;  // off, lost
  states[5] = kLost;
  est[6].pose.x += 0.4;  // near and lost: flagged but not off, so not counted
  states[6] = kLost;
  est[7].stamp += 0.5;  // unmatched (no reference within 0.05 s): not counted
  est[7].pose.x += 9.0;
  est[8].pose.y += 2.0;  // off while tracking
  const OffUpdates o = count_off_updates(est, states, ref);
  EXPECT_EQ(o.off, 4U);
  EXPECT_EQ(o.flagged, 2U);
  EXPECT_EQ(o.tracking(), 2U);
  // Zero exactly when the max error is within the bound.
  EXPECT_GT(compare_trajectories(est, ref).max_error_m, kOffUpdateM);
  EXPECT_EQ(count_off_updates(ref, states, ref).off, 0U);
  // A tighter bound counts more; an estimate without a state counts as tracking.
  const OffUpdates tight = count_off_updates(est, std::span(states).first(5), ref, 0.5);
  EXPECT_EQ(tight.off, 5U);      // 1, 3, 4, 5, 8
  EXPECT_EQ(tight.flagged, 1U);  // only 4: 5's state is past the span
}

TEST(Metrics, PercentilesUseNearestRank) {
  std::vector<double> v;
  for (int k = 100; k >= 1; --k) v.push_back(k);
  const Percentiles p = summarize(v);
  EXPECT_DOUBLE_EQ(p.mean, 50.5);
  EXPECT_DOUBLE_EQ(p.p50, 50.0);
  EXPECT_DOUBLE_EQ(p.p99, 99.0);
  EXPECT_DOUBLE_EQ(p.max, 100.0);
  const Percentiles one = summarize({7.0});
  EXPECT_DOUBLE_EQ(one.p50, 7.0);
  EXPECT_DOUBLE_EQ(one.p99, 7.0);
  EXPECT_DOUBLE_EQ(summarize({}).max, 0.0);
}

}  // namespace
}  // namespace mote::replay
