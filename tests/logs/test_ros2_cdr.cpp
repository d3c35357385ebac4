/// \file
/// CDR decoding in both byte orders, bounds checks on strings and sequences, and the check of
/// MCAP ros2msg schema texts against what the decoders read.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bag_format.hpp"
#include "ros2_builder.hpp"
#include "ros2_messages.hpp"

namespace mote::logs::detail {
namespace {

namespace r2 = mote::test::ros2;

/// The BagDecodeError problem `decode(bytes)` throws, or "" when it does not throw.
template <typename Decode>
std::string problem_of(Decode decode, const std::string& bytes) {
  try {
    (void)decode(bytes);
  } catch (const BagDecodeError& e) {
    return e.problem + " @" + std::to_string(e.offset);
  }
  return "";
}

TEST(Ros2Cdr, LaserScanDecodesTheSameInBothByteOrders) {
  const std::vector<float> ranges{1.5F, NAN, INFINITY, 0.25F};
  for (const bool little : {true, false}) {
    const ScanMessage m =
        decode_laser_scan_cdr(r2::laser_scan(12.5, "laser", ranges, little, -1.0F, 0.5F));
    EXPECT_EQ(m.frame_id, "laser");
    EXPECT_DOUBLE_EQ(m.scan.stamp, 12.5);
    EXPECT_FLOAT_EQ(m.scan.angle_min, -1.0F);
    EXPECT_FLOAT_EQ(m.scan.angle_increment, 0.5F);
    EXPECT_FLOAT_EQ(m.scan.range_max, 10.0F);
    ASSERT_EQ(m.scan.ranges.size(), 4U);
    EXPECT_FLOAT_EQ(m.scan.ranges[0], 1.5F);
    EXPECT_TRUE(std::isnan(m.scan.ranges[1]));  // kept: the sensor models drop no-returns
    EXPECT_TRUE(std::isinf(m.scan.ranges[2]));
  }
}

TEST(Ros2Cdr, OdometryAndTfDecodeTheSameInBothByteOrders) {
  for (const bool little : {true, false}) {
    const OdometryMessage o = decode_odometry_cdr(r2::odometry(3.0, 1.0, -2.0, 0.5, little));
    EXPECT_EQ(o.frame_id, "odom");
    EXPECT_EQ(o.child_frame_id, "base_link");
    EXPECT_NEAR(o.pose.x, 1.0, 1e-12);
    EXPECT_NEAR(o.pose.y, -2.0, 1e-12);
    EXPECT_NEAR(o.pose.theta, 0.5, 1e-12);
    const auto tf =
        decode_tf_cdr(r2::tf_message(4.0,
                                     {{"base_link", "laser", 0.1, 0.2, std::numbers::pi / 2, false},
                                      {"base_link", "flipped", 0.0, 0.0, 0.3, true}},
                                     little));
    ASSERT_EQ(tf.size(), 2U);
    EXPECT_EQ(tf[0].parent, "base_link");
    EXPECT_EQ(tf[0].child, "laser");
    EXPECT_NEAR(tf[0].pose.theta, std::numbers::pi / 2, 1e-12);
    EXPECT_FALSE(tf[0].mirrored);
    EXPECT_NEAR(tf[1].pose.theta, 0.3, 1e-12);  // heading of the x axis survives the roll
    EXPECT_TRUE(tf[1].mirrored);
  }
}

TEST(Ros2Cdr, PoseWithCovarianceStampedDecodes) {
  r2::CdrWriter w(false);
  w.header(1.0, "map").pose(2.0, 3.0, std::sin(0.25), std::cos(0.25));
  for (int k = 0; k < 36; ++k) w.f64(0.0);
  const PoseMessage p = decode_pose_cdr(w.bytes());
  EXPECT_EQ(p.frame_id, "map");
  EXPECT_NEAR(p.pose.x, 2.0, 1e-12);
  EXPECT_NEAR(p.pose.theta, 0.5, 1e-12);
}

TEST(Ros2Cdr, StringsAndSequencesPastTheEndAreErrors) {
  std::string scan = r2::laser_scan(1.0, "laser", {1.0F, 2.0F});
  // frame_id length (bytes 12..15) claims 4 GB.
  std::string long_string = scan;
  long_string.replace(12, 4, std::string(4, '\xff'));
  {
    const std::string p = problem_of(decode_laser_scan_cdr, long_string);
    EXPECT_NE(p.find("header.frame_id: string of 4294967295 bytes runs past the end"),
              std::string::npos)
        << p;
  }
  // The ranges count claims a billion floats.
  std::string long_array = scan;
  const std::size_t count_at = 4 + 8 + 4 + 6 + 2 + 7 * 4;
  long_array.replace(count_at, 4, std::string("\x00\xca\x9a\x3b", 4));
  EXPECT_NE(problem_of(decode_laser_scan_cdr, long_array)
                .find("ranges: 1000000000 elements run past the end of the message"),
            std::string::npos);
  // Every cut of the message is an error, never a read past it.
  for (std::size_t cut = 0; cut + 3 < scan.size(); ++cut) {
    EXPECT_NE(problem_of(decode_laser_scan_cdr, scan.substr(0, cut)), "") << "cut " << cut;
  }
  std::string no_nul = scan;
  no_nul[16 + 5] = 'x';  // "laser\0" -> "laserx"
  EXPECT_NE(problem_of(decode_laser_scan_cdr, no_nul).find("lacks its terminating NUL"),
            std::string::npos);
}

TEST(Ros2Cdr, UnsupportedEncapsulationIsAnError) {
  std::string scan = r2::laser_scan(1.0, "laser", {1.0F});
  scan[1] = 0x03;  // PL_CDR little endian: parameter lists are not plain CDR
  EXPECT_NE(problem_of(decode_laser_scan_cdr, scan).find("unsupported CDR encapsulation 0x03"),
            std::string::npos);
  scan[1] = 0x07;  // plain CDR2: its appendable structs carry headers this decoder does not read
  EXPECT_NE(problem_of(decode_laser_scan_cdr, scan).find("unsupported CDR encapsulation 0x07"),
            std::string::npos);
  EXPECT_NE(problem_of(decode_tf_cdr, std::string("\x00\x01", 2)), "");
}

TEST(Ros2Schema, MatchesTheDecodersFieldsAndNamesTheFirstDifference) {
  EXPECT_EQ(schema_mismatch(Ros2Type::kLaserScan, r2::schema_text("sensor_msgs/msg/LaserScan")),
            std::nullopt);
  EXPECT_EQ(schema_mismatch(Ros2Type::kOdometry, r2::schema_text("nav_msgs/msg/Odometry")),
            std::nullopt);
  EXPECT_EQ(schema_mismatch(Ros2Type::kTf,
                            "# comment\ngeometry_msgs/TransformStamped[] "
                            "transforms\n"),
            std::nullopt);
  const auto swapped = schema_mismatch(
      Ros2Type::kLaserScan, "std_msgs/Header header\nfloat32 angle_max\nfloat32 angle_min\n");
  ASSERT_TRUE(swapped.has_value());
  EXPECT_EQ(*swapped, "field 2 is 'float32 angle_max', expected 'float32 angle_min'");
  EXPECT_TRUE(schema_mismatch(Ros2Type::kTf, "").has_value());
  EXPECT_EQ(ros2_type("sensor_msgs/msg/LaserScan"), Ros2Type::kLaserScan);
  EXPECT_EQ(ros2_type("sensor_msgs/LaserScan"), Ros2Type::kOther);
}

}  // namespace
}  // namespace mote::logs::detail
