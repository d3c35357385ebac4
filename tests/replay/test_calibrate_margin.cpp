// search_margin / best_margin (calibrate.hpp, MarginTrial): the hill-climb over the online
// odometry noise's margin, on score functions whose best margin is known.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/replay/calibrate.hpp"

namespace mote::replay {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Pointwise;

// A fit peaked at `peak` (in log margin), as a run's scan fit is around the margin that tracks
// best; beyond `cliff` the track is lost and the fit collapses.
MarginScorer peaked(double peak, double cliff = 1e9) {
  return [=](double margin) {
    const double off = std::log(margin / peak);
    return MarginTrial{.margin = 0, .fit = margin >= cliff ? -5.0 : 1.5 - off * off, .poses = 500};
  };
}

std::vector<double> margins_of(const std::vector<MarginTrial>& trials) {
  std::vector<double> m;
  for (const MarginTrial& t : trials) m.push_back(t.margin);
  return m;
}

constexpr double kR2 = std::numbers::sqrt2;

TEST(CalibrateMargin, ClimbsUpToThePeakAndOneStepPast) {
  const std::vector<MarginTrial> trials = search_margin(peaked(10.0), 4.0);
  EXPECT_THAT(margins_of(trials), Pointwise(DoubleNear(1e-9), {4.0, 4 * kR2, 8.0, 8 * kR2, 16.0}));
  EXPECT_NEAR(best_margin(trials).margin, 8 * kR2, 1e-9);
  EXPECT_EQ(best_margin(trials).poses, 500U);
}

TEST(CalibrateMargin, ClimbsDownWhenTheFirstStepUpIsWorse) {
  const std::vector<MarginTrial> trials = search_margin(peaked(2.0), 4.0);
  EXPECT_THAT(margins_of(trials),
              Pointwise(DoubleNear(1e-9), {4.0, 4 * kR2, 4 / kR2, 2.0, 2 / kR2}));
  EXPECT_NEAR(best_margin(trials).margin, 2.0, 1e-9);
}

TEST(CalibrateMargin, StopsAtALostTrackAndAtTheBounds) {
  // The fit still rises toward 40, but the track is lost from 16 on: the search stops there
  // and keeps the best margin below it.
  EXPECT_NEAR(best_margin(search_margin(peaked(40.0, 16.0), 4.0)).margin, 8 * kR2, 1e-9);
  // A fit that rises without end stops at the upper bound, one that falls at the lower.
  EXPECT_NEAR(best_margin(search_margin(peaked(1e6), 4.0, 1.0, 16.0)).margin, 16.0, 1e-9);
  const std::vector<MarginTrial> down = search_margin(peaked(1e-6), 4.0, 1.0, 16.0);
  EXPECT_NEAR(best_margin(down).margin, 1.0, 1e-9);
  EXPECT_GE(margins_of(down).back(), 1.0 - 1e-9);
}

TEST(CalibrateMargin, BadArgumentsAreErrors) {
  EXPECT_THROW((void)search_margin(peaked(4.0), 0.5, 1.0, 64.0), Error);
  EXPECT_THROW((void)search_margin(peaked(4.0), 4.0, 0.0, 64.0), Error);
  EXPECT_THROW((void)best_margin({}), Error);
  EXPECT_THAT(margins_of(search_margin(peaked(4.0), 4.0, 4.0, 4.0)), ElementsAre(4.0));
}

}  // namespace
}  // namespace mote::replay
