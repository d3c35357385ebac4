/// \file
/// The CARMEN writer against the CARMEN reader: whatever is written reads back unchanged.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/logs/carmen_writer.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::logs {
namespace {

/// Frames with awkward numbers: random doubles and floats at full precision, odd beam counts,
/// a negative increment, zero ranges and huge stamps.
std::vector<ScanFrame> random_frames(std::uint32_t seed, int count) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> coord(-500.0, 500.0);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<float> range(0.0F, 80.0F);
  std::uniform_int_distribution<int> beams(1, 400);
  std::vector<ScanFrame> frames;
  double stamp = 1.0e9 * std::numbers::e;
  for (int k = 0; k < count; ++k) {
    ScanFrame f;
    stamp += 0.1 * std::numbers::sqrt2;
    f.stamp = stamp;
    f.odometry = {coord(gen), coord(gen), angle(gen)};
    f.scan.stamp = stamp;
    f.scan.angle_min = static_cast<float>(angle(gen));
    f.scan.angle_increment = static_cast<float>(angle(gen) / 300.0);
    f.scan.range_max = range(gen) + 1.0F;
    f.scan.sensor_pose = {coord(gen) / 1000.0, coord(gen) / 1000.0, angle(gen)};
    f.scan.ranges.resize(static_cast<std::size_t>(beams(gen)));
    for (float& r : f.scan.ranges) r = range(gen);
    f.scan.ranges.front() = 0.0F;
    frames.push_back(std::move(f));
  }
  return frames;
}

void expect_same_frame(const ScanFrame& read, const ScanFrame& written) {
  EXPECT_EQ(read.stamp, written.stamp);
  EXPECT_EQ(read.scan.stamp, written.stamp);
  EXPECT_EQ(read.odometry, written.odometry);
  EXPECT_EQ(read.scan.ranges, written.scan.ranges);
  EXPECT_EQ(read.scan.angle_min, written.scan.angle_min);
  EXPECT_EQ(read.scan.angle_increment, written.scan.angle_increment);
  EXPECT_EQ(read.scan.range_max, written.scan.range_max);
  // The log stores the laser pose in the odometry frame; the reader recovers the mounting pose
  // with between(), exact up to the rounding of two rigid transforms.
  EXPECT_NEAR(read.scan.sensor_pose.x, written.scan.sensor_pose.x, 1e-9);
  EXPECT_NEAR(read.scan.sensor_pose.y, written.scan.sensor_pose.y, 1e-9);
  EXPECT_NEAR(read.scan.sensor_pose.theta, written.scan.sensor_pose.theta, 1e-12);
}

std::vector<ScanFrame> write_and_read(const std::vector<ScanFrame>& frames, ReadStats* stats) {
  const auto path = test::temp_dir() / "log.clf";
  write_carmen_log(path, frames);
  auto source = open_carmen_log(path);
  auto read = test::read_all(*source);
  if (stats != nullptr) *stats = source->stats();
  return read;
}

TEST(CarmenWriter, RandomFramesRoundTripExactly) {
  const std::vector<ScanFrame> frames = random_frames(42, 300);
  ReadStats stats;
  const std::vector<ScanFrame> read = write_and_read(frames, &stats);
  ASSERT_EQ(read.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) expect_same_frame(read[k], frames[k]);
  EXPECT_EQ(stats.records_read, 2 * frames.size());  // one ODOM and one ROBOTLASER1 per frame
  EXPECT_EQ(stats.records_skipped, 0U);
}

TEST(CarmenWriter, LinesHaveTheReaderLayout) {
  ScanFrame f;
  f.stamp = 12.5;
  f.odometry = {1.0, 2.0, 0.5};
  f.scan.angle_min = -1.5F;
  f.scan.angle_increment = 0.5F;
  f.scan.range_max = 20.0F;
  f.scan.ranges = {1.0F, 2.5F, 20.0F, 0.25F, 3.0F, 4.0F, 7.0F};
  std::ostringstream out;
  write_carmen_odom(out, f.stamp, f.odometry, {0.5, -0.25});
  EXPECT_EQ(out.str(), "ODOM 1 2 0.5 0.5 -0.25 0 12.5 mote 12.5\n");
  out.str("");
  write_carmen_robotlaser(out, f);
  EXPECT_EQ(out.str(),
            "ROBOTLASER1 0 -1.5 3 0.5 20 0.01 0 7 1 2.5 20 0.25 3 4 7 0 1 2 0.5 1 2 0.5 0 0 0 0 0 "
            "12.5 mote 12.5\n");
}

TEST(CarmenWriter, VelocitiesComeFromConsecutiveOdometry) {
  std::vector<ScanFrame> frames = random_frames(3, 2);
  frames[0].odometry = {0.0, 0.0, 0.0};
  frames[1].odometry = {0.3, 0.0, 0.2};
  frames[1].stamp = frames[0].stamp + 0.5;
  std::ostringstream out;
  write_carmen_log(out, frames);
  EXPECT_THAT(out.str(), ::testing::HasSubstr("ODOM 0.3 0 0.2 0.6 0.4 0 "));
}

TEST(CarmenWriter, RejectsWhatTheReaderWouldReject) {
  ScanFrame f;
  std::ostringstream out;
  EXPECT_THROW(write_carmen_robotlaser(out, f), ConfigError);  // no ranges
  f.scan.ranges = {1.0F, std::numeric_limits<float>::quiet_NaN()};
  EXPECT_THROW(write_carmen_robotlaser(out, f), ConfigError);
  f.scan.ranges = {1.0F, -0.5F};
  EXPECT_THROW(write_carmen_robotlaser(out, f), ConfigError);
  f.scan.ranges = {1.0F, 2.0F};
  f.odometry.x = std::numeric_limits<double>::infinity();
  EXPECT_THROW(write_carmen_robotlaser(out, f), ConfigError);
  EXPECT_THROW(write_carmen_log(test::temp_dir() / "missing" / "x.clf", {}), Error);
}

TEST(CarmenWriter, RecordedIntelLogSurvivesRewriting) {
  MOTE_REQUIRE_DATA(path, "intel/intel.clf");
  auto source = open_carmen_log(path);
  const std::vector<ScanFrame> original = test::read_all(*source);
  ASSERT_GT(original.size(), 900U);
  const std::vector<ScanFrame> read = write_and_read(original, nullptr);
  ASSERT_EQ(read.size(), original.size());
  for (std::size_t k = 0; k < original.size(); ++k) expect_same_frame(read[k], original[k]);
}

}  // namespace
}  // namespace mote::logs
