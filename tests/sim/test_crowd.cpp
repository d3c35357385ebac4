// mote crowd's log transformation (crowd.hpp) on a synthetic log: a robot in a 10 m room that
// drives, turns on the spot, and drives on.
#include "mote/sim/crowd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mote/core/error.hpp"

namespace mote::sim {
namespace {

// 90 scans 1 s apart: 30 driving 0.3 m each, 30 turning 0.2 rad on the spot, 30 driving.
// Every beam reads 5 m (range_max 20 m); 181 beams over 360 degrees.
std::vector<logs::ScanFrame> synthetic_log() {
  std::vector<logs::ScanFrame> frames;
  Pose2 odom{0.0, 0.0, 0.0};
  for (int k = 0; k < 90; ++k) {
    const bool turning = k >= 30 && k < 60;
    if (k > 0) odom = compose(odom, turning ? Pose2{0.0, 0.0, 0.2} : Pose2{0.3, 0.0, 0.0});
    logs::ScanFrame f;
    f.stamp = 100.0 + k;
    f.odometry = odom;
    f.scan.angle_min = static_cast<float>(-std::numbers::pi);
    f.scan.angle_increment = static_cast<float>(2.0 * std::numbers::pi / 180.0);
    f.scan.range_max = 20.0F;
    f.scan.ranges.assign(181, 5.0F);
    frames.push_back(f);
  }
  return frames;
}

TEST(Crowd, FindsTheTurnOnTheSpotAndBlocksMostBeamsThere) {
  const std::vector<logs::ScanFrame> log = synthetic_log();
  const CrowdedLog c = make_crowded_log(log);
  // The 20 s window that turns the most while travelling under 1 m: from the scan before the
  // first turn (scan 29, the window counts the steps after its first scan) to scan 59.
  EXPECT_GE(c.start, 129.0);
  EXPECT_LE(c.end, 159.0);
  EXPECT_EQ(c.crowded_scans, 21U);
  EXPECT_GT(c.blocked_fraction, 0.5);
  ASSERT_EQ(c.frames.size(), log.size());
  for (std::size_t k = 0; k < log.size(); ++k) {
    const bool inside = log[k].stamp >= c.start && log[k].stamp <= c.end;
    EXPECT_EQ(c.frames[k].odometry.theta, log[k].odometry.theta);
    for (std::size_t b = 0; b < log[k].scan.size(); ++b) {
      const float r = c.frames[k].scan.ranges[b];
      if (!inside) {
        EXPECT_EQ(r, 5.0F) << k;
      } else {
        // A person's near side lies between near - radius and far of the ring's centre.
        EXPECT_TRUE(r == 5.0F || (r >= 0.2F && r <= 1.0F)) << k << ' ' << b << ' ' << r;
      }
    }
  }
}

TEST(Crowd, SameSeedSameCrowdAndAnExplicitStart) {
  CrowdOptions o;
  o.start = 110.0;
  o.seconds = 5.0;
  const CrowdedLog a = make_crowded_log(synthetic_log(), o);
  const CrowdedLog b = make_crowded_log(synthetic_log(), o);
  EXPECT_EQ(a.start, 110.0);
  EXPECT_EQ(a.end, 115.0);
  EXPECT_EQ(a.crowded_scans, 6U);
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    EXPECT_EQ(a.frames[k].scan.ranges, b.frames[k].scan.ranges) << k;
  }
  o.seed = 2;
  const CrowdedLog c = make_crowded_log(synthetic_log(), o);
  EXPECT_NE(c.frames[10].scan.ranges, a.frames[10].scan.ranges);
}

TEST(Crowd, OptionsOutOfRangeAreConfigErrors) {
  const auto with = [](auto change) {
    CrowdOptions o;
    change(o);
    return o;
  };
  EXPECT_THROW(
      (void)make_crowded_log(synthetic_log(), with([](CrowdOptions& o) { o.seconds = 0; })),
      ConfigError);
  EXPECT_THROW((void)make_crowded_log(synthetic_log(), with([](CrowdOptions& o) { o.people = 0; })),
               ConfigError);
  EXPECT_THROW(
      (void)make_crowded_log(synthetic_log(), with([](CrowdOptions& o) { o.near_m = 2.0; })),
      ConfigError);
  EXPECT_THROW(
      (void)make_crowded_log(synthetic_log(), with([](CrowdOptions& o) { o.start = 1000.0; })),
      ConfigError);
  EXPECT_THROW((void)make_crowded_log({}), ConfigError);
}

}  // namespace
}  // namespace mote::sim
