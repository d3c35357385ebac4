/// \file
/// ROS 1 bag reader on the recorded DIS bag (bz2 chunks), on copies re-encoded with uncompressed
/// and lz4 chunks, and on small bags built here.

#include <gtest/gtest.h>

#include <numbers>

#include "bag_builder.hpp"
#include "mote/core/error.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::logs {
namespace {

using test::field;
using test::put_u32;
using test::read_all;

std::uint32_t get_u32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8U) | static_cast<unsigned char>(s[at + static_cast<std::size_t>(i)]);
  return v;
}

/// Value of header field `name` in the record header bytes.
std::string header_value(const std::string& header, const std::string& name) {
  for (std::size_t at = 0; at < header.size();) {
    const std::uint32_t len = get_u32(header, at);
    const std::string f = header.substr(at + 4, len);
    if (f.compare(0, name.size() + 1, name + "=") == 0) return f.substr(name.size() + 1);
    at += 4 + len;
  }
  return {};
}

/// The bag with every bz2 chunk decompressed and recompressed as `kind`; index_pos is fixed.
std::string reencode(const std::string& bag, const std::string& kind) {
  std::string out = bag.substr(0, 13);
  std::size_t header_field_at = 0;
  std::uint64_t old_index = 0;
  for (std::size_t at = 13; at < bag.size();) {
    const std::string header = bag.substr(at + 4, get_u32(bag, at));
    const std::size_t data_at = at + 4 + header.size() + 4;
    std::string data = bag.substr(data_at, get_u32(bag, data_at - 4));
    const char op = header_value(header, "op")[0];
    if (op == 0x03) {
      const std::string pos = header_value(header, "index_pos");
      for (int i = 7; i >= 0; --i)
        old_index =
            (old_index << 8U) | static_cast<unsigned char>(pos[static_cast<std::size_t>(i)]);
      header_field_at = out.size() + 4 + header.find("index_pos=") + 10;
    }
    if (at == old_index) {
      std::string pos;
      test::put_u64(pos, out.size());
      out.replace(header_field_at, 8, pos);
    }
    std::string new_header = header;
    if (op == 0x05) {
      const std::uint32_t size = get_u32(header_value(header, "size"), 0);
      std::string raw(size, '\0');
      unsigned int len = size;
      EXPECT_EQ(BZ2_bzBuffToBuffDecompress(raw.data(), &len, data.data(),
                                           static_cast<unsigned int>(data.size()), 0, 0),
                BZ_OK);
      data = test::compress(raw, kind);
      new_header =
          field("op", "\x05") + field("compression", kind) + field("size", test::u32_bytes(size));
    }
    out += test::record(new_header, data);
    at = data_at + get_u32(bag, data_at - 4);
  }
  return out;
}

void expect_dis_bag(const std::filesystem::path& path) {
  auto source = open_scan_log(path);
  const auto frames = read_all(*source);
  ASSERT_EQ(frames.size(), 4427U);
  const ScanFrame& first = frames.front();
  ASSERT_EQ(first.scan.size(), 721U);
  EXPECT_NEAR(first.stamp, 1510757286.108764922, 1e-6);
  EXPECT_FLOAT_EQ(first.scan.angle_min, -1.5707963705062866F);
  EXPECT_FLOAT_EQ(first.scan.angle_increment, 0.004363323096185923F);
  EXPECT_FLOAT_EQ(first.scan.range_max, 30.0F);
  EXPECT_FLOAT_EQ(first.scan.ranges[0], 1.7319999933242798F);
  // The first scan precedes the first odometry message: nearest one.
  EXPECT_DOUBLE_EQ(first.odometry.x, -12.613288879394531);
  EXPECT_DOUBLE_EQ(first.odometry.y, 10.855351448059082);
  EXPECT_NEAR(first.odometry.theta, -2.8862574100494385, 1e-9);
  // /tf base_frame -> laser_frame.
  EXPECT_NEAR(first.scan.sensor_pose.x, 0.07019049674272537, 1e-12);
  EXPECT_NEAR(first.scan.sensor_pose.y, -0.00020143800065852702, 1e-12);
  EXPECT_NEAR(first.scan.sensor_pose.theta, 0.0, 1e-9);
  // Scan 2000 lies between two odometry messages: interpolated.
  EXPECT_NEAR(frames[2000].stamp, 1510757335.9938507, 1e-6);
  EXPECT_NEAR(frames[2000].odometry.x, -1.905190087285279, 1e-6);
  EXPECT_NEAR(frames[2000].odometry.y, 13.709820574330914, 1e-6);
  EXPECT_NEAR(frames[2000].odometry.theta, 0.03897284525620941, 1e-6);
  const ScanFrame& last = frames.back();
  EXPECT_NEAR(last.stamp, 1510757396.4902084, 1e-6);
  EXPECT_NEAR(last.odometry.x, 4.43273401260376, 1e-6);
  EXPECT_NEAR(last.odometry.y, -0.25428298115730286, 1e-6);
  EXPECT_NEAR(last.odometry.theta, -1.1710176467895508, 1e-6);
  for (std::size_t i = 1; i < frames.size(); ++i) ASSERT_GT(frames[i].stamp, frames[i - 1].stamp);
  EXPECT_EQ(source->stats().records_read, 4427U + 5998U + 5484U);
  EXPECT_EQ(source->stats().records_skipped, 0U);
}

TEST(Bag, ReadsTheDisBagWithBz2Chunks) {
  MOTE_REQUIRE_DATA(path, "dis/dis-underground.bag");
  expect_dis_bag(path);
}

TEST(Bag, ReadsTheDisBagReencodedUncompressedAndLz4) {
  MOTE_REQUIRE_DATA(path, "dis/dis-underground.bag");
  const std::string bag = test::read_bytes(path);
  const auto dir = test::temp_dir();
  for (const char* kind : {"none", "lz4"}) {
    SCOPED_TRACE(kind);
    const auto copy = dir / (std::string(kind) + ".bag");
    test::write_bytes(copy, reencode(bag, kind));
    expect_dis_bag(copy);
  }
}

/// Odometry at t = 1 s and 2 s, scans at 0.5, 1.25 and 3 s on frame laser 2 hops below base.
test::BagBuilder small_bag(bool with_odom_topic) {
  test::BagBuilder b;
  b.connection(0, "/front_scan", "sensor_msgs/LaserScan");
  b.connection(1, "/tf_static", "tf2_msgs/TFMessage");
  if (with_odom_topic) b.connection(2, "/wheel_odom", "nav_msgs/Odometry");
  b.connection(3, "/other", "std_msgs/String");
  b.message(3, 0, 0, "xxxx");
  b.message(1, 0, 0, test::tf_message(0, 0, "/base_link", "mount", 0.1, 0.0, std::numbers::pi / 2));
  b.message(1, 0, 0, test::tf_message(0, 0, "mount", "laser", 0.2, 0.0, 0.0));
  b.message(0, 0, 500000000, test::scan_message(0, 500000000, "laser", {1.0F, 2.0F}));
  // Record order is not time order: the reader sorts within the chunk.
  if (with_odom_topic) b.message(2, 2, 0, test::odom_message(2, 0, 2.0, 1.0, 3.0));
  if (with_odom_topic) b.message(2, 1, 0, test::odom_message(1, 0, 1.0, 0.0, -3.0));
  const auto tf_odom = [&](std::uint32_t s, double x, double y, double yaw) {
    b.message(1, s, 0, test::tf_message(s, 0, "odom", "base_link", x, y, yaw));
  };
  if (!with_odom_topic) tf_odom(1, 1.0, 0.0, -3.0);
  if (!with_odom_topic) tf_odom(2, 2.0, 1.0, 3.0);
  b.message(0, 1, 250000000, test::scan_message(1, 250000000, "laser", {3.0F}));
  b.message(0, 3, 0, test::scan_message(3, 0, "laser", {4.0F}));
  return b;
}

TEST(Bag, SmallBagsInEveryCompressionInterpolateOdometryAndChainTransforms) {
  const auto dir = test::temp_dir();
  for (bool odom_topic : {true, false}) {
    for (const char* kind : {"none", "bz2", "lz4"}) {
      SCOPED_TRACE(std::string(kind) + (odom_topic ? " odom topic" : " tf odometry"));
      const auto path = dir / "small.bag";
      test::write_bytes(path, small_bag(odom_topic).finish(kind));
      auto source = open_ros_bag(path);
      const auto frames = read_all(*source);
      ASSERT_EQ(frames.size(), 3U);
      EXPECT_EQ(frames[0].odometry, (Pose2{1.0, 0.0, -3.0}));  // before the first: nearest
      EXPECT_NEAR(frames[1].odometry.x, 1.25, 1e-12);
      EXPECT_NEAR(frames[1].odometry.y, 0.25, 1e-12);
      // -3 to 3 rad is a turn of 2 pi - 6 through pi: a quarter of it from -3.
      EXPECT_NEAR(frames[1].odometry.theta, wrap_angle(-3.0 - 0.25 * (2 * std::numbers::pi - 6.0)),
                  1e-12);
      EXPECT_EQ(frames[2].odometry, (Pose2{2.0, 1.0, 3.0}));  // after the last: nearest
      EXPECT_NEAR(frames[0].scan.sensor_pose.x, 0.1, 1e-12);  // base -> mount -> laser
      EXPECT_NEAR(frames[0].scan.sensor_pose.y, 0.2, 1e-12);
      EXPECT_NEAR(frames[0].scan.sensor_pose.theta, std::numbers::pi / 2, 1e-12);
      EXPECT_EQ(frames[0].scan.ranges, (std::vector<float>{1.0F, 2.0F}));
      EXPECT_EQ(source->stats().records_ignored, 1U);
    }
  }
}

TEST(Bag, TopicOptionSelectsAmongScanTopics) {
  test::BagBuilder b;
  b.connection(0, "/a", "sensor_msgs/LaserScan");
  b.connection(1, "/b", "sensor_msgs/LaserScan");
  b.connection(2, "/odom", "nav_msgs/Odometry");
  b.message(2, 1, 0, test::odom_message(1, 0, 0.0, 0.0, 0.0));
  b.message(0, 1, 0, test::scan_message(1, 0, "", {1.0F}));
  b.message(1, 1, 0, test::scan_message(1, 0, "", {2.0F, 2.0F}));
  const auto path = test::temp_dir() / "two.bag";
  test::write_bytes(path, b.finish("none"));
  ReaderOptions options;
  auto by_default = read_all(*open_ros_bag(path, options));
  ASSERT_EQ(by_default.size(), 1U);
  EXPECT_EQ(by_default[0].scan.size(), 1U);
  options.scan_topic = "/b";
  auto chosen = read_all(*open_ros_bag(path, options));
  ASSERT_EQ(chosen.size(), 1U);
  EXPECT_EQ(chosen[0].scan.size(), 2U);
}

}  // namespace
}  // namespace mote::logs
