/// \file
/// CARMEN log reader on the recorded Intel and Wean logs and on hand-written lines.

#include <gtest/gtest.h>

#include <numbers>

#include "mote/core/error.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::logs {
namespace {

using test::read_all;

TEST(Carmen, ReadsTheIntelLog) {
  MOTE_REQUIRE_DATA(path, "intel/intel.clf");
  auto source = open_scan_log(path);
  const auto frames = read_all(*source);
  ASSERT_EQ(frames.size(), 910U);
  const ScanFrame& first = frames.front();
  ASSERT_EQ(first.scan.size(), 180U);
  EXPECT_DOUBLE_EQ(first.stamp, 32.9068);
  EXPECT_FLOAT_EQ(first.scan.ranges[0], 1.09F);
  EXPECT_FLOAT_EQ(first.scan.ranges[1], 1.08F);
  EXPECT_FLOAT_EQ(first.scan.ranges[179], 1.23F);
  EXPECT_DOUBLE_EQ(first.odometry.x, 0.698035);
  EXPECT_DOUBLE_EQ(first.odometry.y, -0.013284);
  EXPECT_DOUBLE_EQ(first.odometry.theta, -0.460915);
  EXPECT_NEAR(first.scan.angle_min, -std::numbers::pi / 2, 1e-6);
  EXPECT_NEAR(first.scan.angle_increment, std::numbers::pi / 180, 1e-7);
  EXPECT_NEAR(first.scan.beam_angle(179), std::numbers::pi / 2 - std::numbers::pi / 180, 1e-5);
  EXPECT_EQ(first.scan.range_max, kCarmenDefaultMaxRange);
  EXPECT_EQ(first.scan.sensor_pose, Pose2{});  // PARAM robot_frontlaser_offset 0.0
  const ScanFrame& last = frames.back();
  EXPECT_DOUBLE_EQ(last.stamp, 2683.77);
  EXPECT_DOUBLE_EQ(last.odometry.x, -50.563206);
  EXPECT_DOUBLE_EQ(last.odometry.y, -36.104977);
  EXPECT_DOUBLE_EQ(last.odometry.theta, 2.546764);
  EXPECT_FLOAT_EQ(last.scan.ranges[0], 1.01F);
  const ReadStats stats = source->stats();
  EXPECT_EQ(stats.records_read, 910U + 14541U + 2U);  // FLASER + ODOM + PARAM lines
  EXPECT_EQ(stats.records_skipped, 0U);
  EXPECT_TRUE(stats.first_error.empty());
}

TEST(Carmen, ReadsTheWeanLogWithItsLaserOffset) {
  MOTE_REQUIRE_DATA(path, "wean/robotdata1.clf");
  auto source = open_scan_log(path);
  const auto frames = read_all(*source);
  ASSERT_EQ(frames.size(), 713U);
  const ScanFrame& first = frames.front();
  ASSERT_EQ(first.scan.size(), 180U);
  EXPECT_DOUBLE_EQ(first.stamp, 0.025466);
  EXPECT_DOUBLE_EQ(first.odometry.x, -0.9423);
  EXPECT_DOUBLE_EQ(first.odometry.y, -1.3995);
  EXPECT_FLOAT_EQ(first.scan.angle_min, -1.570796F);
  EXPECT_FLOAT_EQ(first.scan.angle_increment, 0.017453F);
  EXPECT_FLOAT_EQ(first.scan.range_max, 81.83F);
  // Laser pose and robot pose are both logged; 25 cm ahead, to the log's 0.1 mm rounding.
  for (const ScanFrame& f : frames) {
    EXPECT_NEAR(f.scan.sensor_pose.x, 0.25, 3e-4);
    EXPECT_NEAR(f.scan.sensor_pose.y, 0.0, 3e-4);
    EXPECT_NEAR(f.scan.sensor_pose.theta, 0.0, 1e-9);
  }
  EXPECT_DOUBLE_EQ(frames.back().stamp, 134.872838);
  EXPECT_DOUBLE_EQ(frames.back().odometry.theta, 2.087414);
}

std::filesystem::path write_log(const std::string& text) {
  const auto path = test::temp_dir() / "tiny.clf";
  test::write_bytes(path, text);
  return path;
}

std::string flaser(int n, const std::string& range = "1.5", const std::string& stamp = "7.25") {
  std::string line = (n > 0 ? "FLASER " : "RLASER ") + std::to_string(std::abs(n));
  for (int i = 0; i < std::abs(n); ++i) line += " " + range;
  return line + " 1 2 0.5 1 2 0.5 " + stamp + " host 7.3\n";
}

TEST(Carmen, HandWrittenLinesCoverEveryMessageType) {
  const std::string text =
      "# comment\nPARAM robot_frontlaser_offset 0.2 host 0\nPARAM robot_rearlaser_offset -0.1\n"
      "ODOM 1 2 0.5 0 0 0 7.0 host 7.0\nSYNC whatever\n" +
      flaser(361) + flaser(-180) + "TRUEPOS 1 2 3\n";
  auto source = open_scan_log(write_log(text));
  const auto frames = read_all(*source);
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_NEAR(frames[0].scan.angle_increment, std::numbers::pi / 360, 1e-7);
  EXPECT_EQ(frames[0].scan.sensor_pose, (Pose2{0.2, 0.0, 0.0}));
  EXPECT_EQ(frames[0].odometry, (Pose2{1.0, 2.0, 0.5}));
  EXPECT_DOUBLE_EQ(frames[0].scan.stamp, 7.25);
  EXPECT_NEAR(frames[1].scan.angle_increment, std::numbers::pi / 180, 1e-7);
  EXPECT_EQ(frames[1].scan.sensor_pose, (Pose2{-0.1, 0.0, std::numbers::pi}));
  EXPECT_EQ(source->stats().records_ignored, 2U);  // SYNC, TRUEPOS
  EXPECT_EQ(source->stats().records_read, 5U);
}

void expect_error(const std::string& text, const std::string& place, const std::string& what) {
  const auto path = write_log(text);
  try {
    auto source = open_carmen_log(path);
    (void)read_all(*source);
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.place(), place);
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(Carmen, MalformedLinesNameFileLineAndField) {
  expect_error(flaser(180) + "FLASER 180 1 2 3\n", "line 2", "expected 189 more fields");
  expect_error(flaser(180, "nan"), "line 1", "field 'range'");
  expect_error(flaser(180, "-1"), "line 1", "negative range");
  expect_error(flaser(180, "1.5", "inf"), "line 1", "ipc_timestamp");
  expect_error("ODOM 1 2 x 0 0 0 7 host 7\n", "line 1", "field 'theta'");
  expect_error("ODOM 1 2 3\n", "line 1", "ODOM");
  expect_error("FLASER 99999999999 1\n", "line 1", "beam count");
  expect_error("FLASER -3 1\n", "line 1", "beam count");
  expect_error("ROBOTLASER1 0 -1.5 3.1 0.5 80 0.01 0 3 1 1\n", "line 1", "too few ranges");
  expect_error("PARAM robot_frontlaser_offset abc\n", "line 1", "field 'offset'");
}

TEST(Carmen, LenientModeSkipsAndCountsMalformedLines) {
  const std::string bad = "FLASER 180 1 2 3\n";
  ReaderOptions options;
  options.lenient = true;
  auto source = open_carmen_log(write_log(flaser(180) + bad + flaser(180) + "ODOM 1 2"), options);
  EXPECT_EQ(read_all(*source).size(), 2U);
  const ReadStats stats = source->stats();
  EXPECT_EQ(stats.records_skipped, 2U);
  EXPECT_EQ(stats.bytes_skipped, bad.size() + 8U);  // the last line has no newline
  EXPECT_NE(stats.first_error.find("line 2"), std::string::npos) << stats.first_error;
}

TEST(Carmen, UnknownExtensionOrMissingFileIsAnInputError) {
  EXPECT_THROW((void)open_scan_log("/tmp/scan.txt"), InputError);
  EXPECT_THROW((void)open_scan_log("/nonexistent/log.clf"), InputError);
}

}  // namespace
}  // namespace mote::logs
