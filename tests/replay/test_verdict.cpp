// The verdict's words (replay/verdict.hpp): the summary's "localized" row never contradicts the
// state the run ends in, "tracking since" is the last unbroken tracking stretch, and the capped
// global set is reported only for a run that drew one.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mote/replay/verdict.hpp"

namespace mote::replay {
namespace {

using S = LocalizationState;

// A run on a 2 x 2 free map whose updates, one per second from stamp 100 s, read `states`.
ReplayResult run_with(const std::vector<S>& states) {
  ReplayResult r{OccupancyGrid(2, 2, 1.0, Pose2{}, std::vector<CellState>(4, CellState::kFree)),
                 LocalizerConfig{}};
  r.first_stamp = 100.0;
  for (std::size_t k = 0; k < states.size(); ++k) {
    UpdateRecord u;
    u.stamp = 100.0 + static_cast<double>(k);
    u.state = states[k];
    r.updates.push_back(u);
    r.trajectory.push_back({u.stamp, {1.0, 1.0, 0.0}});
  }
  return r;
}

std::string localized_row(const RunVerdict& v) { return verdict_rows(v).front().second; }

// The Intel log started at a wrong place (--init-pose 5,-20,1.5) read tracking right after the
// re-localization, then uncertain, then tracking for good: "since" is the start of the last
// stretch, not of the first tracking update.
TEST(Verdict, TrackingSinceIsTheStartOfTheLastUnbrokenTrackingStretch) {
  const RunVerdict v =
      judge_run(run_with({S::kLost, S::kLost, S::kTracking, S::kTracking, S::kUncertain,
                          S::kUncertain, S::kTracking, S::kTracking, S::kTracking}));
  ASSERT_TRUE(v.localized);
  ASSERT_TRUE(v.tracking_since_s.has_value());
  EXPECT_DOUBLE_EQ(*v.tracking_since_s, 6.0);
  EXPECT_EQ(localized_row(v), "yes, tracking since 6.0 s");
}

// Wean with a global start: 16 tracking updates, then the last 4 lost in the cluttered room the
// map does not show. It is not called localized (it ends lost), nor lost (4 of 20): unsure, exit
// status 0, and the words say which updates were lost.
TEST(Verdict, ARunEndingLostOnFewUpdatesIsUnsureNotLocalized) {
  std::vector<S> states(16, S::kTracking);
  states.insert(states.end(), 4, S::kLost);
  const RunVerdict v = judge_run(run_with(states));
  EXPECT_FALSE(v.localized);
  EXPECT_TRUE(v.unsure);
  EXPECT_EQ(exit_status(v), 0);
  EXPECT_EQ(v.lost_last, 4U);
  const std::string row = localized_row(v);
  EXPECT_EQ(row.find("yes"), std::string::npos) << row;
  EXPECT_EQ(row,
            "unsure: tracking until 15.0 s, then lost on the last 4 updates (4 of the last 20 "
            "lost; see the warning)");
  EXPECT_NE(v.warning.find("the last 4 updates are lost"), std::string::npos) << v.warning;
}

TEST(Verdict, ARunLostOnMostOfItsLastUpdatesEndsLost) {
  std::vector<S> states(9, S::kTracking);
  states.insert(states.end(), 11, S::kLost);
  const RunVerdict v = judge_run(run_with(states));
  EXPECT_FALSE(v.localized);
  EXPECT_FALSE(v.unsure);
  EXPECT_EQ(exit_status(v), kExitEndsLost);
  EXPECT_EQ(localized_row(v), "NO, ends lost (see the warning)");
}

// A lost update inside the window does not stop a run that ends tracking from being localized.
TEST(Verdict, ALostUpdateBeforeTheEndStillEndsLocalized) {
  std::vector<S> states(10, S::kTracking);
  states.push_back(S::kLost);
  states.insert(states.end(), 3, S::kUncertain);
  const RunVerdict v = judge_run(run_with(states));
  EXPECT_TRUE(v.localized);
  EXPECT_EQ(exit_status(v), 0);
  EXPECT_EQ(localized_row(v), "yes, 1 of the last 14 updates lost, ends uncertain");
}

ReplayResult capped_run(bool global_start, std::size_t relocalizing_updates) {
  ReplayResult r = run_with(std::vector<S>(5, S::kTracking));
  r.global_set = {.particles = 500000, .per_bin = 5.19, .capped = true};
  r.global_start = global_start;
  for (std::size_t k = 0; k < relocalizing_updates; ++k) r.updates[k].relocalized = 250000;
  return r;
}

// A run from a known pose that never re-localized drew no global set: no "raise max_particles".
TEST(Verdict, TheCappedGlobalSetIsReportedOnlyForTheDrawsThatHappened) {
  EXPECT_EQ(capped_global_set_text(capped_run(false, 0)), "");
  const std::string global = capped_global_set_text(capped_run(true, 0));
  EXPECT_EQ(global,
            "capped at max_particles for the global start: 500000 particles, 5.19 per KLD bin "
            "(asked 6.0); raise max_particles");
  EXPECT_NE(capped_global_set_text(capped_run(false, 1)).find("for 1 re-localization:"),
            std::string::npos);
  EXPECT_NE(capped_global_set_text(capped_run(true, 2))
                .find("the global start and 2 "
                      "re-localizations:"),
            std::string::npos);
  // Below one particle per bin the text says what that means for the answer.
  ReplayResult sparse = capped_run(true, 0);
  sparse.global_set.per_bin = 0.07;
  EXPECT_EQ(capped_global_set_text(sparse),
            "capped at max_particles for the global start: 500000 particles, 0.07 per KLD bin "
            "(asked 6.0); raise max_particles; with fewer than one particle per bin most of the "
            "map's poses were not drawn, so the belief can miss the true place among look-alike "
            "ones");
  ReplayResult not_capped = capped_run(true, 2);
  not_capped.global_set.capped = false;
  EXPECT_EQ(capped_global_set_text(not_capped), "");
}

}  // namespace
}  // namespace mote::replay
