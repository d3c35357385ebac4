// The kidnapped-robot splice: continuity of the odometry, the reference kept as recorded, the
// files it writes, and the Intel log spliced as the team measures recovery.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/logs/carmen_writer.hpp"
#include "mote/sim/kidnap.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::sim {
namespace {

// A robot driving a circle of radius 5 m, 0.1 rad per scan; odometry in a frame rotated and
// shifted from the map (reference) frame, as real odometry is.
struct Recording {
  std::vector<logs::ScanFrame> frames;
  std::vector<logs::StampedPose> reference;
};

Recording circle(std::size_t n) {
  Recording r;
  const Pose2 odom_origin{3.0, -2.0, 0.7};
  for (std::size_t k = 0; k < n; ++k) {
    const double a = 0.1 * static_cast<double>(k);
    const Pose2 truth{5.0 * std::sin(a), 5.0 - 5.0 * std::cos(a), wrap_angle(a)};
    logs::ScanFrame f;
    f.stamp = 10.0 + 0.5 * static_cast<double>(k);
    f.odometry = compose(odom_origin, truth);
    f.scan.ranges = {1.0F, 2.0F, static_cast<float>(k)};
    f.scan.angle_increment = 0.1F;
    f.scan.range_max = 81.83F;
    r.frames.push_back(f);
    r.reference.push_back({f.stamp, truth});
  }
  return r;
}

void expect_pose_near(const Pose2& a, const Pose2& b, double tol = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(wrap_angle(a.theta - b.theta), 0.0, tol);
}

TEST(Kidnap, KeepsTheFirstAndLastPartsAndTheirIncrements) {
  const Recording rec = circle(100);
  const KidnappedLog k = make_kidnapped_log(rec.frames, rec.reference);
  ASSERT_EQ(k.frames.size(), 70U);
  ASSERT_EQ(k.splice_index, 40U);
  EXPECT_DOUBLE_EQ(k.splice_stamp, rec.frames[70].stamp);
  for (std::size_t j = 0; j < 40; ++j) EXPECT_EQ(k.frames[j].odometry, rec.frames[j].odometry);
  // No jump at the splice: the first scan after it has the odometry of the last before it.
  expect_pose_near(k.frames[40].odometry, k.frames[39].odometry);
  // Every later increment is the recorded one; scans and stamps are unchanged.
  for (std::size_t j = 41; j < 70; ++j) {
    const std::size_t src = j + 30;
    expect_pose_near(between(k.frames[j - 1].odometry, k.frames[j].odometry),
                     between(rec.frames[src - 1].odometry, rec.frames[src].odometry));
    EXPECT_EQ(k.frames[j].stamp, rec.frames[src].stamp);
    EXPECT_EQ(k.frames[j].scan.ranges, rec.frames[src].scan.ranges);
  }
}

TEST(Kidnap, ReferenceIsKeptAsRecordedForEveryKeptScan) {
  const Recording rec = circle(100);
  const KidnappedLog k = make_kidnapped_log(rec.frames, rec.reference);
  ASSERT_EQ(k.reference.size(), k.frames.size());
  for (std::size_t j = 0; j < k.frames.size(); ++j) {
    const std::size_t src = j < 40 ? j : j + 30;
    EXPECT_EQ(k.reference[j], rec.reference[src]);
  }
  // Carried from the pose at scan 39 to the pose at scan 70, the odometry not noticing.
  const Pose2 a = rec.reference[39].pose;
  const Pose2 b = rec.reference[70].pose;
  EXPECT_NEAR(k.carried_m, std::hypot(b.x - a.x, b.y - a.y), 1e-12);
  EXPECT_GT(k.carried_m, 5.0);
}

TEST(Kidnap, RejectsFractionsThatOverlapOrLeaveNothing) {
  const Recording rec = circle(10);
  const auto with_first = [](double f) {
    KidnapOptions o;
    o.keep_first = f;
    return o;
  };
  EXPECT_THROW((void)make_kidnapped_log(rec.frames, rec.reference, with_first(0.8)), ConfigError);
  EXPECT_THROW((void)make_kidnapped_log(rec.frames, rec.reference, with_first(0.0)), ConfigError);
  EXPECT_THROW((void)make_kidnapped_log(rec.frames, rec.reference, with_first(0.05)), ConfigError);
}

// The files read back as written: the CARMEN log gives the spliced frames, the TUM the reference.
TEST(Kidnap, WritesALogAndReferenceThatReadBack) {
  const Recording rec = circle(50);
  const auto dir = test::temp_dir();
  const std::filesystem::path in = dir / "in.clf";
  logs::write_carmen_log(in, rec.frames);
  auto source = logs::open_scan_log(in);
  const KidnapFiles files = make_kidnap_files(*source, rec.reference, dir / "out");
  auto back = logs::open_scan_log(files.log);
  const auto frames = test::read_all(*back);
  ASSERT_EQ(frames.size(), files.spliced.frames.size());
  for (std::size_t j = 0; j < frames.size(); ++j) {
    EXPECT_EQ(frames[j].odometry, files.spliced.frames[j].odometry);
    EXPECT_EQ(frames[j].stamp, files.spliced.frames[j].stamp);
  }
  const auto tum = logs::read_tum(files.reference);
  ASSERT_EQ(tum.size(), files.spliced.reference.size());
  for (std::size_t j = 0; j < tum.size(); ++j) {
    EXPECT_NEAR(tum[j].stamp, files.spliced.reference[j].stamp, 1e-9);
    expect_pose_near(tum[j].pose, files.spliced.reference[j].pose, 1e-6);
  }
}

TEST(Kidnap, IntelLogCarriesTheRobotAbout27Metres) {
  MOTE_REQUIRE_DATA(log, "intel/intel.clf");
  MOTE_REQUIRE_DATA(ref, "intel/intel.gt.tum");
  auto source = logs::open_scan_log(log);
  const auto reference = logs::read_tum(ref);
  const auto dir = test::temp_dir();
  const KidnapFiles files = make_kidnap_files(*source, reference, dir);
  const KidnappedLog& k = files.spliced;
  EXPECT_EQ(k.splice_index, 364U);                 // floor(0.4 * 910)
  EXPECT_EQ(k.frames.size(), 364U + 273U);         // + floor(0.3 * 910)
  EXPECT_EQ(k.reference.size(), k.frames.size());  // every Intel scan has a reference pose
  EXPECT_NEAR(k.carried_m, 27.0, 3.0);
  const Pose2 step = between(k.frames[363].odometry, k.frames[364].odometry);
  EXPECT_NEAR(std::hypot(step.x, step.y), 0.0, 1e-9);
}

}  // namespace
}  // namespace mote::sim
