// When a lost filter re-localizes (RelocalizationSchedule), fed sequences of states directly:
// the waits double while it stays lost, a filter that flaps between lost and tracking keeps its
// back-off, a sustained tracking stretch resets it, and a global search that has not settled
// never re-localizes.
#include "mote/engine/relocalization.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace mote {
namespace {

constexpr LocalizationState kLost = LocalizationState::kLost;
constexpr LocalizationState kTracking = LocalizationState::kTracking;
constexpr LocalizationState kUncertain = LocalizationState::kUncertain;

// The updates (0-based) after which a re-localization was due.
std::vector<int> due_at(RelocalizationSchedule& s, const std::vector<LocalizationState>& states,
                        bool focused = true) {
  std::vector<int> out;
  for (int k = 0; k < static_cast<int>(states.size()); ++k) {
    if (s.after_update(states[static_cast<std::size_t>(k)], focused)) out.push_back(k);
  }
  return out;
}

TEST(RelocalizationSchedule, WaitsDoubleWhileLostUpToTheLongest) {
  RelocalizationSchedule s;
  ASSERT_FALSE(s.after_update(kTracking, true));
  const std::vector<int> due = due_at(s, std::vector<LocalizationState>(400, kLost));
  // Waits of 3, 6, 12, 24, 48, then 96 lost updates.
  const std::vector<int> expected{2, 8, 20, 44, 92, 188, 284, 380};
  EXPECT_EQ(due, expected);
}

// The flapping filter of Wean's closed doors: lost three updates, tracking one, again and
// again. Each tracking update reset the wait, so it re-localized every fourth update.
TEST(RelocalizationSchedule, AFlappingFilterKeepsItsBackOff) {
  RelocalizationSchedule s;
  std::vector<LocalizationState> flapping;
  for (int k = 0; k < 100; ++k) flapping.insert(flapping.end(), {kLost, kLost, kLost, kTracking});
  ASSERT_FALSE(s.after_update(kTracking, true));
  const std::vector<int> due = due_at(s, flapping);
  EXPECT_LE(due.size(), 2U) << "a global set about every fourth update";
  EXPECT_GE(due.size(), 1U);
  EXPECT_GT(s.wait(), RelocalizationSchedule::kFirstAfter);
}

TEST(RelocalizationSchedule, ASustainedTrackingStretchResetsTheWait) {
  RelocalizationSchedule s;
  ASSERT_FALSE(s.after_update(kTracking, true));
  EXPECT_EQ(due_at(s, {kLost, kLost, kLost}), std::vector<int>{2});
  EXPECT_EQ(s.wait(), 6U);
  EXPECT_TRUE(due_at(s, std::vector<LocalizationState>(9, kTracking)).empty());
  EXPECT_EQ(s.wait(), 6U);  // nine tracking updates are not enough
  (void)s.after_update(kTracking, true);
  EXPECT_EQ(s.wait(), RelocalizationSchedule::kFirstAfter);
  EXPECT_EQ(due_at(s, {kLost, kLost, kLost}), std::vector<int>{2});
}

TEST(RelocalizationSchedule, AGlobalSearchThatHasNotSettledNeverRelocalizes) {
  // Lost and uncertain, the belief spread out (not focused): a wrong map, a converging start.
  RelocalizationSchedule s;
  std::vector<LocalizationState> searching;
  for (int k = 0; k < 50; ++k) searching.insert(searching.end(), {kLost, kLost, kUncertain});
  EXPECT_TRUE(due_at(s, searching, false).empty());
  EXPECT_FALSE(s.settled());
  // Converged where the scans do not fit: focused, lost. Settled after kConvergedAfter
  // focused updates in a row; then the usual first wait.
  const std::vector<int> due = due_at(s, std::vector<LocalizationState>(12, kLost), true);
  EXPECT_TRUE(s.settled());
  EXPECT_EQ(due, std::vector<int>{9});
  s.reset(false);  // a global start
  EXPECT_FALSE(s.settled());
  s.reset(true);  // a start around a given pose: lost there calls for a global set
  EXPECT_TRUE(s.settled());
  EXPECT_EQ(due_at(s, std::vector<LocalizationState>(4, kLost), false), std::vector<int>{2});
}

}  // namespace
}  // namespace mote
