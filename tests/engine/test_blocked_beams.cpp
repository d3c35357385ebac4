// The unmapped-obstacle filter (blocked_beams.hpp) through the Localizer, on the recorded Intel
// map with simulated scans: a ring of people around the robot blocks most beams; the filter
// leaves those beams out while tracking, and leaves every beam in while the belief is diffuse.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "mote/engine/localizer.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"
#include "mote_test/scan_simulator.hpp"

namespace mote {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// The first reference pose of the Intel log (intel.gt.tum), a free spot in the map.
constexpr Pose2 kStart{0.600266, -0.032033, -0.354646};

// Seven of every ten beams cut short at 0.5 m, as by people standing close around the robot.
LaserScan crowded(LaserScan scan) {
  for (std::size_t b = 0; b < scan.size(); ++b) {
    if (b % 10 < 7) scan.ranges[b] = 0.5F;
  }
  return scan;
}

// Crowded beams whose true reading is beyond the crowd by clearly more than the hit band
// (0.54 m for mote's mixture and the simulator's 20 m range, blocked_beams.cpp): these must go.
std::size_t clearly_short(const LaserScan& clear) {
  std::size_t n = 0;
  for (std::size_t b = 0; b < clear.size(); ++b) {
    if (b % 10 < 7 && clear.ranges[b] > 0.5F + 0.7F) ++n;
  }
  return n;
}

class BlockedBeams : public ::testing::Test {
 protected:
  void SetUp() override {
    MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
    map_ = std::make_unique<OccupancyGrid>(load_map(yaml));
  }

  static LocalizerConfig config(bool filter) {
    LocalizerConfig c;
    c.min_particles = c.max_particles = 2000;
    c.max_beams = 180;  // every simulated beam, so the crowd's share is known
    c.update_min_d = c.update_min_a = 0.0;
    c.unmapped_obstacle_filter = filter;
    return c;
  }

  // A Localizer started at kStart (5 cm, 2 degrees) that has weighed the scan there.
  std::unique_ptr<Localizer> started(bool filter, test::ScanSimulator& sim) const {
    auto localizer = std::make_unique<Localizer>(*map_, config(filter));
    const Eigen::Matrix3d cov =
        Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 2 * kDeg * 2 * kDeg).asDiagonal();
    localizer->initialize(kStart, cov);
    localizer->update(kStart, sim.scan_at(kStart));
    return localizer;
  }

  // Tracks from kStart for 10 clear updates, then `crowd_updates` crowded ones while the robot
  // keeps moving; returns the last position error, and the blocked and clearly short beam
  // counts of the crowded updates.
  struct Run {
    double error_m = 0.0;
    std::size_t blocked = 0;
    std::size_t clearly_short = 0;
  };
  Run track(bool filter, int crowd_updates) {
    test::ScanSimulator sim(*map_, 11);
    const std::unique_ptr<Localizer> started_localizer = started(filter, sim);
    Localizer& localizer = *started_localizer;
    Pose2 truth = kStart;
    Run run;
    for (int k = 0; k < 10 + crowd_updates; ++k) {
      truth = sim.drive(truth, 0.1);
      LaserScan scan = sim.scan_at(truth);
      if (k >= 10) {
        run.clearly_short += clearly_short(scan);
        scan = crowded(scan);
      }
      EXPECT_TRUE(localizer.update(truth, scan));  // exact odometry: only the scan misleads
      if (k >= 10) run.blocked += localizer.last_update().blocked_beams;
    }
    const Pose2 est = localizer.estimate().best().mean;
    run.error_m = std::hypot(est.x - truth.x, est.y - truth.y);
    return run;
  }

  std::unique_ptr<OccupancyGrid> map_;
};

TEST_F(BlockedBeams, CrowdedBeamsAreLeftOutWhileTracking) {
  const Run run = track(true, 15);
  // Every crowded beam that ends clearly short of its wall is left out; those with a wall
  // within the hit band behind the person may stay (the likelihood field sees a near miss).
  ASSERT_GT(run.clearly_short, 500U);
  EXPECT_GE(run.blocked, run.clearly_short);
  EXPECT_LE(run.blocked, 15U * 126U);  // never more than the crowd's beams
  EXPECT_LT(run.error_m, 0.1);
}

TEST_F(BlockedBeams, OffLeavesEveryBeamIn) {
  const Run run = track(false, 15);
  EXPECT_EQ(run.blocked, 0U);
}

TEST_F(BlockedBeams, DiffuseBeliefKeepsEveryBeam) {
  // Global localization: the first updates' belief is spread over the whole map, where short
  // readings are "blocked" at most poses; they are what tells the poses apart, so all stay.
  Localizer localizer(*map_, config(true));
  localizer.initialize_global();
  test::ScanSimulator sim(*map_, 5);
  Pose2 truth = kStart;
  ASSERT_TRUE(localizer.update(truth, crowded(sim.scan_at(truth))));
  EXPECT_EQ(localizer.last_update().blocked_beams, 0U);
  truth = sim.drive(truth, 0.1);
  ASSERT_TRUE(localizer.update(truth, crowded(sim.scan_at(truth))));
  EXPECT_EQ(localizer.last_update().blocked_beams, 0U);
}

TEST_F(BlockedBeams, EveryBeamBlockedMeansMotionOnly) {
  test::ScanSimulator sim(*map_, 3);
  const std::unique_ptr<Localizer> started_localizer = started(true, sim);
  Localizer& localizer = *started_localizer;
  Pose2 truth = kStart;
  for (int k = 0; k < 5; ++k) {
    truth = sim.drive(truth, 0.1);
    localizer.update(truth, sim.scan_at(truth));
  }
  truth = sim.drive(truth, 0.1);
  LaserScan scan = sim.scan_at(truth);
  for (float& r : scan.ranges) r = 0.3F;  // a person right in front of every beam
  ASSERT_TRUE(localizer.update(truth, scan));
  const UpdateStats& s = localizer.last_update();
  EXPECT_EQ(s.outcome, UpdateOutcome::kUpdated);
  EXPECT_EQ(s.beams, 0U);
  EXPECT_EQ(s.blocked_beams, 180U);
  EXPECT_NE(s.reason.find("unmapped_obstacle_filter"), std::string::npos) << s.reason;
  const Pose2 est = localizer.estimate().best().mean;
  EXPECT_LT(std::hypot(est.x - truth.x, est.y - truth.y), 0.1);
}

}  // namespace
}  // namespace mote
