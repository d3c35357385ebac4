// search_margin / best_margin (calibrate.hpp, MarginTrial): the hill-climb over the online
// odometry noise's margin, on score functions whose best margin is known.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"

namespace mote::calibrate {
namespace {

using ::testing::ElementsAre;

// A fit peaked at `peak` (in log margin), as a run's scan fit is around the margin that tracks
// best, `scale` nats deep over a factor e, each trial with the given spread between its runs;
// beyond `cliff` the track is lost and the fit collapses.
MarginScorer peaked(double peak, double cliff = 1e9, double scale = 1.0, double spread = 0.0) {
  return [=](double margin) {
    const double off = std::log(margin / peak);
    return MarginTrial{.margin = 0,
                       .fit = margin >= cliff ? -5.0 : 1.5 - scale * off * off,
                       .spread = spread,
                       .poses = 500};
  };
}

std::vector<double> margins_of(const std::vector<MarginTrial>& trials) {
  std::vector<double> m;
  for (const MarginTrial& t : trials) m.push_back(t.margin);
  return m;
}

TEST(CalibrateMargin, ClimbsUpToThePeakAndOneStepPast) {
  const std::vector<MarginTrial> trials = search_margin(peaked(10.0), 4.0);
  // The steps are sqrt(2) apart, to three digits: what the config writes reads back the same.
  EXPECT_THAT(margins_of(trials), ElementsAre(4.0, 5.66, 8.0, 11.3, 16.0));
  EXPECT_EQ(best_margin(trials).margin, 11.3);
  EXPECT_EQ(best_margin(trials).poses, 500U);
}

TEST(CalibrateMargin, ClimbsDownWhenTheFirstStepUpIsWorse) {
  const std::vector<MarginTrial> trials = search_margin(peaked(2.0), 4.0);
  EXPECT_THAT(margins_of(trials), ElementsAre(4.0, 5.66, 2.83, 2.0, 1.41));
  EXPECT_EQ(best_margin(trials).margin, 2.0);
}

TEST(CalibrateMargin, StopsAtALostTrackAndAtTheBounds) {
  // The fit still rises toward 40, but the track is lost from 15.5 on: the search stops at 16
  // and keeps the best margin below it.
  EXPECT_EQ(best_margin(search_margin(peaked(40.0, 15.5), 4.0)).margin, 11.3);
  // A fit that rises without end stops at the upper bound, one that falls at the lower.
  EXPECT_EQ(best_margin(search_margin(peaked(1e6), 4.0, 1.0, 16.0)).margin, 16.0);
  const std::vector<MarginTrial> down = search_margin(peaked(1e-6), 4.0, 1.0, 16.0);
  EXPECT_EQ(best_margin(down).margin, 1.0);
  EXPECT_EQ(margins_of(down).back(), 1.0);
}

TEST(CalibrateMargin, StepsOnlyWhenTheGainExceedsTheRunsSpread) {
  // Peak at 10 (scale 0.1): the steps up gain 0.052, 0.027, 0.0035 and lose 0.021 nats.
  EXPECT_EQ(best_margin(search_margin(peaked(10.0, 1e9, 0.1, 0.0), 4.0)).margin, 11.3);
  // The same fit with runs that disagree by 0.003 on either side: 4 -> 5.66 and 5.66 -> 8
  // gain more than 0.006, 8 -> 11.3 only 0.0035, so the search stops at 8.
  const std::vector<MarginTrial> trials = search_margin(peaked(10.0, 1e9, 0.1, 0.003), 4.0);
  EXPECT_EQ(best_margin(trials).margin, 8.0);
  EXPECT_THAT(margins_of(trials), ElementsAre(4.0, 5.66, 8.0, 11.3));
  EXPECT_FALSE(trials.back().accepted);
  // Runs that disagree more than any step gains: the margin stays at the start.
  EXPECT_EQ(best_margin(search_margin(peaked(10.0, 1e9, 0.1, 0.05), 4.0)).margin, 4.0);
}

TEST(CalibrateMargin, BadArgumentsAreErrors) {
  EXPECT_THROW((void)search_margin(peaked(4.0), 0.5, 1.0, 64.0), Error);
  EXPECT_THROW((void)search_margin(peaked(4.0), 4.0, 0.0, 64.0), Error);
  EXPECT_THROW((void)best_margin({}), Error);
  EXPECT_THAT(margins_of(search_margin(peaked(4.0), 4.0, 4.0, 4.0)), ElementsAre(4.0));
}

}  // namespace
}  // namespace mote::calibrate
