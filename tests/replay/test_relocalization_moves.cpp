// What each re-localization did to the reported pose (relocalization_moves.hpp): a false alarm
// ridden out settles where the tracked pose, carried by the odometry, would be; a jump settles
// metres away; a re-localization that never reads tracking again is counted apart.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mote/replay/relocalization_moves.hpp"

namespace mote::replay {
namespace {

using S = LocalizationState;

// Updates one per second; the odometry drives 1 m along x per update from (0, 0, 0); the
// reported pose follows the odometry 5 m off in y (the map -> odom offset), except where
// `jump_from` >= 0: from that update on it reads 20 m further along y.
std::vector<UpdateRecord> drive(const std::vector<S>& states, const std::vector<int>& relocalized,
                                int jump_from = -1) {
  std::vector<UpdateRecord> out;
  for (std::size_t k = 0; k < states.size(); ++k) {
    UpdateRecord u;
    u.stamp = static_cast<double>(k);
    u.state = states[k];
    u.odometry = {static_cast<double>(k), 0.0, 0.0};
    const bool jumped = jump_from >= 0 && static_cast<int>(k) >= jump_from;
    u.refined = {static_cast<double>(k), jumped ? 25.0 : 5.0, 0.0};
    out.push_back(u);
  }
  for (const int k : relocalized) out[static_cast<std::size_t>(k)].relocalized = 1000;
  return out;
}

TEST(RelocalizationMoves, AFalseAlarmRiddenOutDidNotMoveThePose) {
  const auto updates = drive(
      {S::kTracking, S::kLost, S::kLost, S::kLost, S::kUncertain, S::kTracking, S::kTracking}, {3});
  const RelocalizationMoves m = relocalization_moves(updates);
  ASSERT_EQ(m.moves.size(), 1U);
  EXPECT_EQ(m.moves[0].update, 3U);
  EXPECT_EQ(m.moves[0].settled_update, 5U);
  EXPECT_NEAR(m.moves[0].moved_m, 0.0, 1e-12);
  EXPECT_EQ(m.moved, 0U);
  EXPECT_EQ(m.unsettled, 0U);
}

TEST(RelocalizationMoves, AJumpToAnotherPlaceMovedThePose) {
  const auto updates =
      drive({S::kTracking, S::kLost, S::kLost, S::kLost, S::kUncertain, S::kTracking}, {3}, 4);
  const RelocalizationMoves m = relocalization_moves(updates);
  ASSERT_EQ(m.moves.size(), 1U);
  EXPECT_NEAR(m.moves[0].moved_m, 20.0, 1e-12);
  EXPECT_EQ(m.moved, 1U);
}

TEST(RelocalizationMoves, OneThatNeverTracksAgainIsUnsettledAndAFirstUpdateOneHasNoDistance) {
  // The first re-localization gives way to a second before any tracking update; the second
  // never settles. One on the first update settles but has no pose before it.
  const RelocalizationMoves never =
      relocalization_moves(drive({S::kTracking, S::kLost, S::kLost, S::kLost, S::kLost}, {2, 4}));
  ASSERT_EQ(never.moves.size(), 2U);
  EXPECT_EQ(never.unsettled, 2U);
  EXPECT_TRUE(std::isnan(never.moves[0].moved_m));
  const RelocalizationMoves first = relocalization_moves(drive({S::kUncertain, S::kTracking}, {0}));
  ASSERT_EQ(first.moves.size(), 1U);
  EXPECT_EQ(first.moves[0].settled_update, 1U);
  EXPECT_TRUE(std::isnan(first.moves[0].moved_m));
  EXPECT_EQ(first.moved + first.unsettled, 0U);
  EXPECT_TRUE(relocalization_moves({}).moves.empty());
}

}  // namespace
}  // namespace mote::replay
