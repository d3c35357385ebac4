// Filter-level bad input (issue 9): each case has the behaviour documented in localizer.hpp, and
// the particle set never holds a NaN afterwards. A synthetic 5 x 5 m room keeps the test
// independent of ../shared/data and fast under sanitizers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/engine/localizer.hpp"
#include "mote_test/scan_simulator.hpp"

namespace mote {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A 100 x 100 cell room (5 cm cells) with walls around it and a pillar off centre, so that
// scans pin down the pose.
OccupancyGrid room(CellState inside = CellState::kFree) {
  constexpr int kSize = 100;
  std::vector<CellState> cells(kSize * kSize, inside);
  for (int j = 0; j < kSize; ++j) {
    for (int i = 0; i < kSize; ++i) {
      const bool wall = i < 2 || j < 2 || i >= kSize - 2 || j >= kSize - 2;
      const bool pillar = i >= 60 && i < 70 && j >= 25 && j < 40;
      if (wall || pillar) cells[static_cast<std::size_t>(j * kSize + i)] = CellState::kOccupied;
    }
  }
  return {kSize, kSize, 0.05, Pose2{}, std::move(cells)};
}

LocalizerConfig small_config(int particles = 300) {
  LocalizerConfig c;
  c.min_particles = c.max_particles = particles;
  c.update_min_d = c.update_min_a = 0.0;
  c.threads = 1;
  return c;
}

bool all_finite(const ConstParticleView& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!std::isfinite(p.x[i]) || !std::isfinite(p.y[i]) || !std::isfinite(p.theta[i]) ||
        std::isnan(p.logw[i])) {
      return false;
    }
  }
  return true;
}

class BadInput : public ::testing::Test {
 protected:
  BadInput() : map_(room()), sim_(map_, 5), filter_(map_, small_config()) {
    filter_.initialize(truth_, Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
    EXPECT_TRUE(filter_.update(odom_, sim_.scan_at(truth_)));
  }
  // Feeds a scan that must be rejected with `outcome`, then checks that nothing moved.
  void expect_rejected(const Pose2& odometry, const LaserScan& scan, UpdateOutcome outcome) {
    const Pose2 before = filter_.estimate().best().mean;
    EXPECT_FALSE(filter_.update(odometry, scan));
    EXPECT_EQ(filter_.last_update().outcome, outcome);
    EXPECT_FALSE(filter_.last_update().reason.empty());
    EXPECT_EQ(filter_.estimate().best().mean, before);
    EXPECT_TRUE(all_finite(filter_.particles()));
  }
  // One ordinary step: the robot moves 0.2 m ahead, odometry too.
  void ordinary_step() {
    truth_ = compose(truth_, {0.2, 0.0, 0.0});
    odom_ = compose(odom_, {0.2, 0.0, 0.0});
    EXPECT_TRUE(filter_.update(odom_, sim_.scan_at(truth_)));
    EXPECT_TRUE(all_finite(filter_.particles()));
  }
  double error() const { return test::position_error(filter_.estimate().best().mean, truth_); }

  OccupancyGrid map_;
  test::ScanSimulator sim_;
  Localizer filter_;
  Pose2 truth_{1.5, 2.5, 0.0};
  Pose2 odom_{10.0, -3.0, 0.5};
};

TEST_F(BadInput, ScanWithEveryReadingInvalidIsRejected) {
  LaserScan scan = sim_.scan_at(truth_);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    scan.ranges[i] = i % 3 == 0 ? kNaN : (i % 3 == 1 ? -1.0F : scan.range_min / 2);
  }
  expect_rejected(compose(odom_, {0.2, 0, 0}), scan, UpdateOutcome::kRejectedScan);
}

TEST_F(BadInput, ScanAllAtMaxRangeIsRejectedByTheLikelihoodField) {
  LaserScan scan = sim_.scan_at(truth_);
  for (float& r : scan.ranges) r = scan.range_max;
  expect_rejected(compose(odom_, {0.2, 0, 0}), scan, UpdateOutcome::kRejectedScan);
  ordinary_step();  // and the filter goes on
}

TEST_F(BadInput, ScanAllAtMaxRangeIsWeighedByTheBeamModel) {
  LocalizerConfig c = small_config();
  c.laser_model_type = LaserModel::kBeam;
  Localizer beam(map_, c);
  beam.initialize(truth_, Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  LaserScan scan = sim_.scan_at(truth_);
  for (float& r : scan.ranges) r = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(beam.update(odom_, scan));
  EXPECT_TRUE(beam.update(compose(odom_, {0.2, 0, 0}), scan));
  EXPECT_TRUE(all_finite(beam.particles()));
}

// The particle columns, for comparing two filters bit for bit.
std::vector<float> columns(const ConstParticleView& p) {
  std::vector<float> out;
  for (const float* c : {p.x, p.y, p.theta, p.logw}) out.insert(out.end(), c, c + p.size());
  return out;
}

TEST_F(BadInput, BeamModelScanWithoutAPositiveRangeMaxLeavesTheFilterAsItWas) {
  // Such a scan cannot be ray-cast; it must be refused before motion moves the particles, or
  // the next update applies the same motion again (update() must not half-run).
  LocalizerConfig c = small_config();
  c.laser_model_type = LaserModel::kBeam;
  c.laser_max_range = -1.0;  // the scan's own range_max
  Localizer fed(map_, c);
  Localizer fresh(map_, c);
  const LaserScan first = sim_.scan_at(truth_);  // the simulator's noise moves on per scan
  for (Localizer* f : {&fed, &fresh}) {
    f->initialize(truth_, Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
    ASSERT_TRUE(f->update(odom_, first));
  }
  const Pose2 odom1 = compose(odom_, {0.2, 0.0, 0.0});
  const Pose2 truth1 = compose(truth_, {0.2, 0.0, 0.0});
  for (const float bad_max : {0.0F, -1.0F, std::numeric_limits<float>::infinity()}) {
    LaserScan bad = sim_.scan_at(truth1);
    bad.range_max = bad_max;
    try {
      EXPECT_FALSE(fed.update(odom1, bad)) << "range_max " << bad_max;
      EXPECT_EQ(fed.last_update().outcome, UpdateOutcome::kRejectedScan);
      EXPECT_FALSE(fed.last_update().reason.empty());
    } catch (const Error& e) {
      ADD_FAILURE() << "range_max " << bad_max << " threw: " << e.what();
    }
  }
  // Beam angles that overflow float are refused up front too.
  LaserScan huge = sim_.scan_at(truth1);
  huge.angle_min = 3e38F;
  huge.angle_increment = 3e38F;
  try {
    EXPECT_FALSE(fed.update(odom1, huge));
    EXPECT_EQ(fed.last_update().outcome, UpdateOutcome::kRejectedScan);
  } catch (const Error& e) {
    ADD_FAILURE() << "overflowing beam angles threw: " << e.what();
  }
  const Pose2 odom2 = compose(odom1, {0.2, 0.0, 0.0});
  const LaserScan good = sim_.scan_at(compose(truth1, {0.2, 0.0, 0.0}));
  ASSERT_TRUE(fed.update(odom2, good));
  ASSERT_TRUE(fresh.update(odom2, good));
  EXPECT_EQ(columns(fed.particles()), columns(fresh.particles()));
  EXPECT_EQ(fed.last_update().step, fresh.last_update().step);
}

TEST_F(BadInput, ScanWithNonFiniteGeometryIsRejected) {
  const Pose2 next = compose(odom_, {0.2, 0, 0});
  LaserScan scan = sim_.scan_at(truth_);
  scan.angle_increment = kNaN;
  expect_rejected(next, scan, UpdateOutcome::kRejectedScan);
  scan = sim_.scan_at(truth_);
  scan.angle_min = std::numeric_limits<float>::infinity();
  expect_rejected(next, scan, UpdateOutcome::kRejectedScan);
  scan = sim_.scan_at(truth_);
  scan.range_max = kNaN;
  expect_rejected(next, scan, UpdateOutcome::kRejectedScan);
  scan = sim_.scan_at(truth_);
  scan.sensor_pose.theta = std::nan("");
  expect_rejected(next, scan, UpdateOutcome::kRejectedScan);
}

TEST_F(BadInput, ScanWithFarMoreBeamsThanUsedIsDecimated) {
  LaserScan scan = sim_.scan_at(truth_);
  // 100000 readings over a full turn and a half: beams past 2 pi simply wrap around.
  scan.angle_increment = static_cast<float>(3 * std::numbers::pi / 100000);
  scan.ranges.assign(100000, 1.0F);
  truth_ = compose(truth_, {0.2, 0, 0});
  odom_ = compose(odom_, {0.2, 0, 0});
  EXPECT_TRUE(filter_.update(odom_, scan));
  // Selected: weighed, or left out as cut short by something unmapped (every reading is 1 m).
  const UpdateStats& s = filter_.last_update();
  EXPECT_EQ(s.beams + s.blocked_beams, static_cast<std::size_t>(small_config().max_beams));
  EXPECT_TRUE(all_finite(filter_.particles()));
}

TEST_F(BadInput, NonFiniteOdometryIsRejected) {
  const LaserScan scan = sim_.scan_at(truth_);
  const double inf = std::numeric_limits<double>::infinity();
  expect_rejected({std::nan(""), 0, 0}, scan, UpdateOutcome::kRejectedOdometry);
  expect_rejected({0, inf, 0}, scan, UpdateOutcome::kRejectedOdometry);
  expect_rejected({0, 0, -inf}, scan, UpdateOutcome::kRejectedOdometry);
}

TEST_F(BadInput, OdometryJumpOfKilometresIsAResetNotMotion) {
  // The odometry frame restarts 5 km away while the robot stands still.
  odom_ = compose(odom_, {5000.0, -1200.0, 2.0});
  expect_rejected(odom_, sim_.scan_at(truth_), UpdateOutcome::kRejectedOdometry);
  EXPECT_NE(filter_.last_update().reason.find("odometry reset"), std::string::npos);
  // Steps count from the new odometry pose: the filter keeps tracking.
  for (int k = 0; k < 5; ++k) ordinary_step();
  EXPECT_LT(error(), 0.1);
}

TEST(BadInputConfig, ZeroParticlesIsAConfigErrorAndOneParticleRuns) {
  const OccupancyGrid map = room();
  EXPECT_THROW(Localizer(map, small_config(0)), ConfigError);
  LocalizerConfig bad = small_config();
  bad.odom_jump_max_d = 0.0;
  EXPECT_THROW(Localizer(map, bad), ConfigError);

  Localizer one(map, small_config(1));
  test::ScanSimulator sim(map, 9);
  Pose2 truth{1.5, 2.5, 0.0};
  one.initialize(truth, Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  for (int k = 0; k < 20; ++k) {
    truth = compose(truth, {0.1, 0.0, 0.0});
    EXPECT_TRUE(one.update(truth, sim.scan_at(truth)));
    ASSERT_EQ(one.particles().size(), 1U);
    EXPECT_TRUE(all_finite(one.particles()));
  }
}

TEST(BadInputConfig, MapWithoutAFreeCellCannotBeGloballyInitialized) {
  const OccupancyGrid solid = room(CellState::kOccupied);
  Localizer filter(solid, small_config());
  try {
    filter.initialize_global();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("free"), std::string::npos) << e.what();
  }
  // Tracking on it still runs: every scan is explained equally badly, never NaN.
  filter.initialize({1.0, 1.0, 0.0}, Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  test::ScanSimulator sim(room(), 4);
  EXPECT_TRUE(filter.update({0, 0, 0}, sim.scan_at({1.0, 1.0, 0.0})));
  EXPECT_TRUE(filter.update({0.2, 0, 0}, sim.scan_at({1.2, 1.0, 0.0})));
  EXPECT_TRUE(all_finite(filter.particles()));
}

}  // namespace
}  // namespace mote
