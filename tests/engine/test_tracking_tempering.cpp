// tracking_tempering (localizer_config.hpp): with adaptive tempering, the configured exponent
// replaces the adaptive search once the belief has settled, and only then. On the recorded
// Intel map with simulated scans: tracking from a known pose uses it from the first update on,
// global localization keeps the search while the belief is spread over the map.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mote/engine/localizer.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"
#include "mote_test/scan_simulator.hpp"

namespace mote {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr Pose2 kStart{0.600266, -0.032033, -0.354646};  // first Intel reference pose
constexpr double kTracking = 0.37;

class TrackingTempering : public ::testing::Test {
 protected:
  void SetUp() override {
    MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
    map_ = std::make_unique<OccupancyGrid>(load_map(yaml));
  }

  static LocalizerConfig config(double tracking) {
    LocalizerConfig c;
    c.min_particles = c.max_particles = 2000;
    c.update_min_d = c.update_min_a = 0.0;
    c.tracking_tempering = tracking;
    return c;
  }

  // The exponents of five updates while tracking from kStart (5 cm, 2 degrees).
  std::vector<double> tracked(double tracking) const {
    Localizer localizer(*map_, config(tracking));
    localizer.initialize(kStart,
                         Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 4 * kDeg * kDeg).asDiagonal());
    test::ScanSimulator sim(*map_, 7);
    Pose2 truth = kStart;
    std::vector<double> taus;
    for (int k = 0; k < 5; ++k) {
      EXPECT_TRUE(localizer.update(truth, sim.scan_at(truth)));
      taus.push_back(localizer.last_update().tempering);
      truth = sim.drive(truth, 0.1);
    }
    return taus;
  }

  std::unique_ptr<OccupancyGrid> map_;
};

TEST_F(TrackingTempering, SettledBeliefUsesTheConfiguredExponent) {
  // The first update weighs the initial set, which is already one tight cluster.
  for (const double tau : tracked(kTracking)) EXPECT_EQ(tau, kTracking);
}

TEST_F(TrackingTempering, OffKeepsTheAdaptiveSearch) {
  for (const double tau : tracked(0.0)) {
    EXPECT_GT(tau, 0.0);
    EXPECT_NE(tau, kTracking);
  }
}

TEST_F(TrackingTempering, GlobalLocalizationKeepsTheAdaptiveSearch) {
  // Spread over the whole map, the belief is no few tight hypotheses: the search chooses, and
  // against a dense scan far from most particles it chooses far below the tracking exponent.
  Localizer localizer(*map_, config(kTracking));
  localizer.initialize_global();
  test::ScanSimulator sim(*map_, 5);
  ASSERT_TRUE(localizer.update(kStart, sim.scan_at(kStart)));
  EXPECT_LT(localizer.last_update().tempering, kTracking);
}

// UpdateStats::log_evidence, the scan's predictive log-likelihood under the filter's prior: a
// cloud around the true pose explains the scan far better than one half a metre away.
TEST(LogEvidence, IsHigherForAPriorAroundTheTruth) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const OccupancyGrid map = load_map(yaml);
  LocalizerConfig c;
  c.min_particles = c.max_particles = 2000;
  c.likelihood_tempering = 1.0;
  c.z_hit = 0.9;
  c.z_rand = 0.1;
  c.sigma_hit = 0.05;
  test::ScanSimulator sim(map, 3);
  const LaserScan scan = sim.scan_at(kStart);
  const auto evidence_from = [&](const Pose2& mean) {
    Localizer localizer(map, c);
    localizer.initialize(mean,
                         Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 4 * kDeg * kDeg).asDiagonal());
    EXPECT_TRUE(localizer.update(kStart, scan));
    return localizer.last_update().log_evidence;
  };
  const double at_truth = evidence_from(kStart);
  const double off = evidence_from({kStart.x + 0.5, kStart.y, kStart.theta});
  EXPECT_TRUE(std::isfinite(at_truth));
  EXPECT_TRUE(std::isfinite(off));
  // 60 beams at sigma_hit 0.05 m: half a metre off costs tens of nats.
  EXPECT_GT(at_truth, off + 10.0) << at_truth << " " << off;
}

// motion_noise_margin is the online odometry-noise fit's variance factor: with odometry that
// under-reports every step by 10%, the adapted alphas grow with it.
TEST(MotionNoiseMargin, ScalesTheAdaptedAlphas) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const OccupancyGrid map = load_map(yaml);
  const auto adapted = [&](double margin) {
    LocalizerConfig c;
    c.min_particles = c.max_particles = 1000;
    c.update_min_d = c.update_min_a = 0.0;
    c.motion_noise_margin = margin;
    Localizer localizer(map, c);
    localizer.initialize(kStart,
                         Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 4 * kDeg * kDeg).asDiagonal());
    test::ScanSimulator sim(map, 11);
    Pose2 truth = kStart;
    Pose2 odometry = kStart;
    for (int k = 0; k < 40; ++k) {
      EXPECT_TRUE(localizer.update(odometry, sim.scan_at(truth)));
      const Pose2 next = sim.drive(truth, 0.2);
      const Pose2 step = between(truth, next);
      odometry = compose(odometry, {0.9 * step.x, 0.9 * step.y, 0.9 * step.theta});
      truth = next;
    }
    const OdometryAlphas a = localizer.last_update().alphas;
    return a.alpha1 + a.alpha2 + a.alpha3 + a.alpha4;
  };
  const double at4 = adapted(4.0);
  const double at8 = adapted(8.0);
  EXPECT_GT(at4, 4 * 0.002);  // above the fit's floor, so the margin shows
  EXPECT_GT(at8, 1.5 * at4);
  EXPECT_LT(at8, 2.5 * at4);
}

}  // namespace
}  // namespace mote
