// The scan matcher: from a start pose off by tens of centimetres it finds the pose the scan was
// taken from on the Intel map, shrugs off readings of things the map does not hold, and its
// covariance says which directions the scan fixes (a corridor fixes the lateral position only).
#include "mote/engine/scan_match.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"
#include "mote_test/scan_simulator.hpp"

namespace mote {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Robot-frame endpoints of a scan's finite readings.
std::vector<Point2> endpoints(const LaserScan& scan) {
  std::vector<Point2> ends;
  for (std::size_t b = 0; b < scan.ranges.size(); ++b) {
    const float r = scan.ranges[b];
    if (!(r < scan.range_max)) continue;
    const double a = scan.beam_angle(b);
    ends.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return ends;
}

class ScanMatchOnIntel : public ::testing::Test {
 protected:
  void SetUp() override {
    MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
    map_ = std::make_unique<OccupancyGrid>(load_map(yaml));
    field_ = std::make_unique<SignedDistanceField>(*map_, 2.0F);
  }
  std::unique_ptr<OccupancyGrid> map_;
  std::unique_ptr<SignedDistanceField> field_;
};

// From 19 cm and 4 degrees off, along a drive through the lab. The interpolated field ripples
// at the scale of a cell where the map draws a slanted wall as a staircase, so the match may
// stop a cell short of the pose (measured: 0-4.6 cm on these poses, 10 cm on one), no worse.
TEST_F(ScanMatchOnIntel, FindsThePoseTheScanWasTakenFrom) {
  test::ScanSimulator sim(*map_, 3, {.unknown_blocks = false});
  const ScanMatcher matcher(*field_, {.scale = 0.2});
  Pose2 truth{-2.0, 1.5, 0.4};  // a free spot: the simulator's drive keeps it there
  std::vector<double> errors;
  for (int k = 0; k < 40; ++k, truth = sim.drive(truth, 1.0)) {
    const std::vector<Point2> ends = endpoints(sim.scan_at(truth, 0.01));
    if (ends.size() < 90) continue;  // too open to say much
    const Pose2 start{truth.x + 0.15, truth.y - 0.12, truth.theta + 4 * kDeg};
    const ScanMatch m = matcher.match(ends, start);
    SCOPED_TRACE(k);
    EXPECT_LT(test::position_error(m.pose, truth), 0.12);
    EXPECT_LT(test::heading_error(m.pose, truth), 1.0 * kDeg);
    EXPECT_GT(m.hit_share, 0.9);
    EXPECT_GT(m.covariance.determinant(), 0.0);
    errors.push_back(test::position_error(m.pose, truth));
  }
  ASSERT_GT(errors.size(), 20U);
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.03);  // the start was 0.19 m off
}

// Convergence is reported: a search stopped by its iteration cap far from the minimum is not
// a fix (the Localizer neither reports it nor feeds it to the odometry-noise fit).
TEST_F(ScanMatchOnIntel, SaysWhetherItConverged) {
  test::ScanSimulator sim(*map_, 3, {.unknown_blocks = false});
  const Pose2 truth{-2.0, 1.5, 0.4};
  const std::vector<Point2> ends = endpoints(sim.scan_at(truth, 0.01));
  const Pose2 start{truth.x + 0.15, truth.y - 0.12, truth.theta + 4 * kDeg};
  const ScanMatch full = ScanMatcher(*field_, {.scale = 0.2}).match(ends, start);
  EXPECT_TRUE(full.converged);
  EXPECT_LT(full.iterations, 20);
  const ScanMatch capped =
      ScanMatcher(*field_, {.scale = 0.2, .max_iterations = 1}).match(ends, start);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.iterations, 1);
  EXPECT_FALSE(ScanMatcher(*field_, {}).match({}, start).converged);
}

TEST_F(ScanMatchOnIntel, ReadingsOfUnmappedThingsPullLittle) {
  test::ScanSimulator sim(*map_, 5, {.unknown_blocks = false});
  const ScanMatcher matcher(*field_, {.scale = 0.2});
  const Pose2 truth{-2.0, 1.5, 0.4};
  std::vector<Point2> ends = endpoints(sim.scan_at(truth, 0.01));
  // A third of the readings cut short at random, as a crowd around the robot would.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  for (std::size_t b = 0; b < ends.size(); b += 3)
    ends[b] = {ends[b].x * u(rng), ends[b].y * u(rng)};
  const ScanMatch m = matcher.match(ends, {truth.x + 0.1, truth.y + 0.1, truth.theta - 3 * kDeg});
  EXPECT_LT(test::position_error(m.pose, truth), 0.04);
  EXPECT_LT(test::heading_error(m.pose, truth), 1.0 * kDeg);
  EXPECT_LT(m.hit_share, 0.8);  // the cut readings are not hits
}

// A corridor 2 m wide along x on a synthetic grid: the walls fix y and the heading; x only by
// the corridor's ends, 10 m away, which the readings do not see.
TEST(ScanMatch, CovarianceIsLargeAlongACorridorAndSmallAcrossIt) {
  const int w = 400;
  const int h = 60;
  const double res = 0.05;
  std::vector<CellState> cells(static_cast<std::size_t>(w * h), CellState::kFree);
  for (int i = 0; i < w; ++i) {
    cells[static_cast<std::size_t>(9 * w + i)] = CellState::kOccupied;   // y = -1 m
    cells[static_cast<std::size_t>(50 * w + i)] = CellState::kOccupied;  // y = +1 m
  }
  const OccupancyGrid grid(w, h, res, Pose2{-10.0, -1.5, 0.0}, std::move(cells));
  const SignedDistanceField field(grid, 2.0F);
  const ScanMatcher matcher(field, {.scale = 0.1});
  // Readings hit both walls' faces (y = -1.0 + res and y = +1.0 - ... within half a cell).
  std::vector<Point2> ends;
  for (double x = -4.0; x <= 4.0; x += 0.1) {
    ends.push_back({x, -1.0 + 0.5 * res + 0.0});
    ends.push_back({x, 1.0 - 0.5 * res});
  }
  const ScanMatch m = matcher.match(ends, {0.0, 0.05, 0.02});
  EXPECT_NEAR(m.pose.y, 0.0, 0.02);
  EXPECT_NEAR(m.pose.theta, 0.0, 0.01);
  EXPECT_GT(m.covariance(0, 0), 100.0 * m.covariance(1, 1));
}

TEST(ScanMatch, WithoutReadingsReturnsTheStartAndRefusesABadScale) {
  const OccupancyGrid grid(4, 4, 0.1, Pose2{}, std::vector<CellState>(16, CellState::kFree));
  const SignedDistanceField field(grid, 1.0F);
  const ScanMatcher matcher(field, {});
  const Pose2 start{0.2, 0.1, 0.3};
  const ScanMatch m = matcher.match({}, start);
  EXPECT_EQ(m.pose, start);
  EXPECT_EQ(m.endpoints, 0U);
  EXPECT_EQ(m.hit_share, 0.0);
  EXPECT_THROW(ScanMatcher(field, {.scale = 0.0}), ConfigError);
}

}  // namespace
}  // namespace mote
