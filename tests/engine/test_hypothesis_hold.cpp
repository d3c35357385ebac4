// Holding the tracked place against a challenger: the rule on its own, and through the
// Localizer on a floor plan of two identical wings, where a global start must say `uncertain`
// with two places, report one of them steadily, and take the right one once the robot sees
// what tells the wings apart.
#include "mote/engine/hypothesis_hold.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "mote/engine/localizer.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote_test/scan_simulator.hpp"

namespace mote {
namespace {

TEST(HypothesisHold, OtherPlaceIsAShiftOfTheEndpointsBeyondTheRange) {
  const Pose2 a{0.0, 0.0, 0.0};
  EXPECT_FALSE(HypothesisHold::other_place(a, {2.0, 0.0, 0.0}, 4.0));
  EXPECT_TRUE(HypothesisHold::other_place(a, {5.0, 0.0, 0.0}, 4.0));
  // 1 m plus 1 rad times 4 m: 5 m.
  EXPECT_TRUE(HypothesisHold::other_place(a, {1.0, 0.0, 1.0}, 4.0));
  EXPECT_FALSE(HypothesisHold::other_place(a, {1.0, 0.0, 0.5}, 4.0));
  EXPECT_TRUE(HypothesisHold::other_place(a, {std::nan(""), 0.0, 0.0}, 4.0));
}

TEST(HypothesisHold, McNemarsStatisticCountsCorrelatedReadingsAsFewer) {
  // 30 against 10: z = 20 / sqrt(40) = 3.16; from readings correlated by 2, 2.24.
  EXPECT_NEAR(HypothesisHold::z({.only_challenger = 30, .only_held = 10}, 1.0), 3.162, 1e-3);
  EXPECT_NEAR(HypothesisHold::z({.only_challenger = 10, .only_held = 30}, 1.0), -3.162, 1e-3);
  EXPECT_NEAR(HypothesisHold::z({.only_challenger = 30, .only_held = 10}, 2.0), 2.236, 1e-3);
  EXPECT_NEAR(HypothesisHold::z({.only_challenger = 30, .only_held = 10}, 0.5), 3.162, 1e-3);
  EXPECT_EQ(HypothesisHold::z({}, 1.0), 0.0);
}

TEST(HypothesisHold, TheBoundarySpendsTheSignificanceOverEveryLook) {
  EXPECT_NEAR(HypothesisHold::boundary(1), 3.29, 0.01);  // 0.001 / 2
  EXPECT_NEAR(HypothesisHold::boundary(2), 3.59, 0.01);
  EXPECT_NEAR(HypothesisHold::boundary(10), 4.29, 0.01);
  EXPECT_NEAR(HypothesisHold::boundary(100), 5.20, 0.01);
  // A challenge between two places that differ only by noise: 10 discordant readings a scan,
  // split evenly at random, for 1000 scans in each of 400 runs (deterministic draws); at the
  // level of a single look for every scan 2.6 % of them handed over.
  std::mt19937_64 rng(5);
  int handed_over = 0;
  for (int run = 0; run < 400; ++run) {
    HypothesisHold hold;
    hold.challenge();
    for (int k = 0; k < 1000; ++k) {
      HitDifference d;
      for (int r = 0; r < 10; ++r) ((rng() & 1U) != 0 ? d.only_challenger : d.only_held) += 1;
      if (hold.after_scan(d, 1.0, 1.0, 0.0)) {
        ++handed_over;
        break;
      }
    }
  }
  EXPECT_LE(handed_over, 2) << "of 400";  // 0.001 nominal: 0.4 expected
}

TEST(HypothesisHold, TheChallengerWinsOnEvidenceSummedOverOneRangeOfTravel) {
  HypothesisHold hold;
  hold.challenge();
  // 20 against 0 is z = 4.47 in one scan, but the first scan starts the travel.
  EXPECT_FALSE(hold.after_scan({.only_challenger = 20}, 1.0, 0.5, 2.0));
  EXPECT_FALSE(hold.after_scan({}, 1.0, 1.0, 2.0));  // 1 m: not yet a new view
  // 21 against 1: z = 4.26 beyond the third look's boundary, 3.76.
  EXPECT_TRUE(hold.after_scan({.only_challenger = 1, .only_held = 1}, 1.0, 1.0, 2.0));
  // Evidence both ways that never leans beyond chance: no switch, however far.
  hold.challenge();
  for (int k = 0; k < 20; ++k) {
    EXPECT_FALSE(hold.after_scan({.only_challenger = 5, .only_held = 4}, 1.0, 1.0, 2.0));
  }
  EXPECT_EQ(hold.scans(), 20);
  // The held place explaining the scans better starts the evidence over.
  hold.challenge();
  EXPECT_FALSE(hold.after_scan({.only_challenger = 8}, 1.0, 1.0, 2.0));
  EXPECT_FALSE(hold.after_scan({.only_held = 40}, 1.0, 1.0, 2.0));  // z = -4.62 past -3.59
  EXPECT_EQ(hold.scans(), 0);
  EXPECT_TRUE(hold.active());
  // However far the robot went, one scan is not a run.
  hold.challenge();
  EXPECT_FALSE(hold.after_scan({.only_challenger = 50}, 1.0, 100.0, 2.0));
  EXPECT_TRUE(hold.after_scan({.only_challenger = 50}, 1.0, 100.0, 2.0));
  hold.end();
  EXPECT_FALSE(hold.active());
}

// Two wings of 13 m x 8 m, the right one the left turned by 180 degrees about (15, 5): a pose
// (x, y, theta) in one looks exactly like (30 - x, 10 - y, theta + pi) in the other. Each wing
// has a partition with a gap at its inner end and a box in its outer half; only the left wing
// has a pillar in the corner behind its partition, out of sight from the outer half.
constexpr double kResolution = 0.1;

class TwoWings {
 public:
  TwoWings() : cells_(300 * 100, CellState::kOccupied) {
    carve(1.0, 1.0, 14.0, 9.0);  // left wing, in wing coordinates (u, v) from (1, 1)
    wall(7.5, 1.0, 7.7, 6.5);    // partition u = 6.5, v in [0, 5.5]: the gap is v in [5.5, 8]
    wall(10.5, 2.0, 11.5, 3.0);  // a box in the outer (east) half
    turn_left_wing_into_right();
    wall(1.5, 1.5, 3.5, 3.5);  // the pillar: left wing only, behind the partition
  }
  [[nodiscard]] OccupancyGrid grid() const {
    return {300, 100, kResolution, Pose2{0.0, 0.0, 0.0}, cells_};
  }

 private:
  void fill(double x0, double y0, double x1, double y1, CellState s) {
    for (int j = static_cast<int>(y0 / kResolution); j < static_cast<int>(y1 / kResolution); ++j) {
      for (int i = static_cast<int>(x0 / kResolution); i < static_cast<int>(x1 / kResolution);
           ++i) {
        cells_[static_cast<std::size_t>(j) * 300 + static_cast<std::size_t>(i)] = s;
      }
    }
  }
  void carve(double x0, double y0, double x1, double y1) { fill(x0, y0, x1, y1, CellState::kFree); }
  void wall(double x0, double y0, double x1, double y1) {
    fill(x0, y0, x1, y1, CellState::kOccupied);
  }
  // Cell (i, j) of the right half becomes cell (299 - i, 99 - j) of the left: a turn by 180
  // degrees about the map's centre.
  void turn_left_wing_into_right() {
    for (int j = 0; j < 100; ++j) {
      for (int i = 150; i < 300; ++i) {
        cells_[static_cast<std::size_t>(j) * 300 + static_cast<std::size_t>(i)] =
            cells_[static_cast<std::size_t>(99 - j) * 300 + static_cast<std::size_t>(299 - i)];
      }
    }
  }

  std::vector<CellState> cells_;
};

// The robot's true poses: 0.3 m steps between waypoints (left wing, map frame), heading along
// the way.
std::vector<Pose2> path_through(const std::vector<Point2>& waypoints) {
  std::vector<Pose2> poses;
  for (std::size_t w = 0; w + 1 < waypoints.size(); ++w) {
    const Point2 a = waypoints[w];
    const Point2 b = waypoints[w + 1];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    const double heading = std::atan2(b.y - a.y, b.x - a.x);
    const int steps = std::max(1, static_cast<int>(std::round(length / 0.3)));
    for (int s = 0; s < steps; ++s) {
      const double f = static_cast<double>(s) / steps;
      poses.push_back({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), heading});
    }
  }
  return poses;
}

Pose2 twin(const Pose2& p) {
  return {30.0 - p.x, 10.0 - p.y, wrap_angle(p.theta + std::numbers::pi)};
}

// What one global run on the two wings did.
struct WingsRun {
  bool settled_uncertain = true;  // never `tracking` in the second half of the outer loops
  int two_places = 0;             // updates there that counted two places
  int settled = 0;                // updates there
  int jumps = 0;                  // reported pose moving 5 m or more between updates there
  int elsewhere = 0;  // reported pose there 0.5 m or more from the truth and from its twin
  int tracking_right_at_end = 0;  // final updates in a row tracking within 0.3 m
  int held = 0;                   // updates whose report stayed on the tracked place
};

WingsRun run_on_two_wings(std::uint64_t seed) {
  const OccupancyGrid map = TwoWings{}.grid();
  LocalizerConfig config;  // mote's defaults, every scan weighed
  config.max_particles = 200000;
  config.update_min_d = 0.0;
  config.update_min_a = 0.0;
  config.seed = seed;
  Localizer filter(map, config);
  filter.initialize_global();
  test::ScanSimulator sim(map, 7);
  // Loops in the outer half, whose views never reach past the partition's end.
  const std::vector<Point2> outer{{11.5, 4.5}, {13.0, 6.0}, {12.0, 8.0}, {11.0, 6.0}};
  std::vector<Point2> loops;
  for (int k = 0; k < 4; ++k) loops.insert(loops.end(), outer.begin(), outer.end());
  loops.push_back(outer.front());
  // Then through the gap into the inner half, where the pillar is in view.
  const std::vector<Point2> inner{{11.5, 4.5}, {11.0, 7.8}, {8.5, 7.8}, {5.0, 7.5},
                                  {4.5, 5.0},  {6.0, 4.5},  {6.0, 7.5}, {3.0, 8.0}};
  const std::vector<Pose2> first = path_through(loops);
  const std::vector<Pose2> second = path_through(inner);
  Pose2 odometry{0.0, 0.0, 0.0};
  Pose2 last = first.front();
  // Wheel odometry that slips a little: 2 % of each step's length and 0.01 rad per step (with
  // perfect odometry the twins' clouds stay as tight as each other and neither ever outweighs
  // the other, which no robot's do).
  std::mt19937 slips(static_cast<std::uint32_t>(seed));
  std::normal_distribution<double> normal;
  const auto feed = [&](const Pose2& truth) {
    Pose2 step = between(last, truth);
    const double scale = 1.0 + 0.02 * normal(slips);
    step = {step.x * scale, step.y * scale, step.theta + 0.01 * normal(slips)};
    odometry = compose(odometry, step);
    last = truth;
    filter.update(odometry, sim.scan_at(truth));
    return filter.last_update();
  };
  WingsRun run;
  Pose2 before = filter.estimate().refined.pose;
  for (std::size_t k = 0; k < first.size(); ++k) {
    const UpdateStats u = feed(first[k]);
    run.held += u.held ? 1 : 0;
    const Pose2 reported = filter.estimate().refined.pose;
    if (k >= first.size() / 2) {
      run.settled_uncertain = run.settled_uncertain && u.state != LocalizationState::kTracking;
      run.two_places += u.places == 2 ? 1 : 0;
      ++run.settled;
      run.jumps += test::position_error(reported, before) > 5.0 ? 1 : 0;
      run.elsewhere += test::position_error(reported, first[k]) >= 0.5 &&
                               test::position_error(reported, twin(first[k])) >= 0.5
                           ? 1
                           : 0;
    }
    before = reported;
  }
  for (const Pose2& truth : second) {
    const UpdateStats u = feed(truth);
    const bool right = test::position_error(filter.estimate().refined.pose, truth) < 0.3;
    run.tracking_right_at_end =
        u.state == LocalizationState::kTracking && right ? run.tracking_right_at_end + 1 : 0;
  }
  return run;
}

// Global localization with seeds 1-6: no seed's reported pose jumps between the wings, and on
// most seeds (more than half) the filter says `uncertain` with two places in the outer half,
// reporting one of them, and tracks the right wing once the pillar is in view. Measured with
// the slipping odometry (AVX-512 kernels, GCC): 5 of 6, the hold engaged on 4 seeds, with the
// odometry-noise fit before and after its confidence bound; with perfect odometry, 5 of 6 (4
// with the generic kernels) before the bound and 6 of 6 after, but no twin ever outweighed the
// other, so the hold went untested. A seed that fails lost the right wing's cluster in the
// global search among four look-alike places (each wing is nearly symmetric in itself too)
// before keep_places could hold it. Without keep_places (an earlier build of it): 3 of 6.
TEST(HypothesisHoldOnTwoWings, LookAlikeWingsStayUncertainUntilThePillarTellsThemApart) {
  int uncertain_runs = 0;
  int right_at_end = 0;
  int held = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const WingsRun run = run_on_two_wings(seed);
    EXPECT_EQ(run.jumps, 0) << "seed " << seed;
    const bool two =
        run.settled_uncertain && run.two_places >= run.settled * 9 / 10 && run.elsewhere == 0;
    uncertain_runs += two ? 1 : 0;
    right_at_end += run.tracking_right_at_end >= 5 ? 1 : 0;
    held += run.held;
  }
  EXPECT_GT(held, 0) << "the heavier twin never challenged the reported wing";
  EXPECT_GT(uncertain_runs, 3) << "of 6";
  EXPECT_GT(right_at_end, 3) << "of 6";
}

}  // namespace
}  // namespace mote
