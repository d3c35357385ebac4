// Golden tests: every message mote publishes equals, byte for byte, what Cyclone DDS makes of an
// idlc sample of the same IDL with the same values, and a reader of the idlc type decodes it.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "cyclone_golden.hpp"
#include "diagnostic_msgs.h"
#include "idl_samples.hpp"
#include "mote/ros/messages.hpp"
#include "nav2_msgs.h"
#include "ros2_messages.hpp"
#include "sensor_msgs.h"
#include "tf2_msgs.h"

namespace mote::ros::test {
namespace {

void expect_header(const std_msgs_msg_dds__Header_& got, const Header& want) {
  EXPECT_EQ(got.stamp_.sec_, want.stamp.sec);
  EXPECT_EQ(got.stamp_.nanosec_, want.stamp.nanosec);
  EXPECT_STREQ(got.frame_id_, want.frame_id.c_str());
}

void expect_pose(const geometry_msgs_msg_dds__Pose_& got, const Pose2& want) {
  EXPECT_EQ(got.position_.x_, want.x);
  EXPECT_EQ(got.position_.y_, want.y);
  EXPECT_EQ(got.position_.z_, 0.0);
  EXPECT_NEAR(2.0 * std::atan2(got.orientation_.z_, got.orientation_.w_), want.theta, 1e-12);
  EXPECT_EQ(got.orientation_.x_, 0.0);
  EXPECT_EQ(got.orientation_.y_, 0.0);
}

using Golden = CycloneTest;

TEST_F(Golden, PoseWithCovarianceStamped) {
  PoseWithCovarianceStamped msg;
  msg.header = {{1733540000, 123456789}, "map"};
  msg.pose = {1.5, -2.25, 0.7};
  msg.covariance = {0.25, 0.01, 0.002, 0.01, 0.16, -0.003, 0.002, -0.003, 0.05};
  geometry_msgs_msg_dds__PoseWithCovarianceStamped_ s{};
  fill(s.header_, msg.header);
  s.pose_.pose_ = idl_pose(msg.pose);
  // amcl's layout: x, y and yaw are rows and columns 0, 1 and 5 of the 6x6 matrix.
  const std::array<std::size_t, 3> axes = {0, 1, 5};
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c)
      s.pose_.covariance_[6 * axes[r] + axes[c]] = msg.covariance[3 * r + c];
  }
  CycloneChannel channel(domain(), geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc);
  const std::string ours = encode_pose_with_covariance(msg);
  expect_same_bytes(ours, channel.serialize(&s));
  channel.decode(ours, [&](const void* p) {
    const auto& d = *static_cast<const geometry_msgs_msg_dds__PoseWithCovarianceStamped_*>(p);
    expect_header(d.header_, msg.header);
    expect_pose(d.pose_.pose_, msg.pose);
    for (int k = 0; k < 36; ++k) EXPECT_EQ(d.pose_.covariance_[k], s.pose_.covariance_[k]) << k;
    EXPECT_EQ(d.pose_.covariance_[7], 0.16);
    EXPECT_EQ(d.pose_.covariance_[35], 0.05);
  });
  // What mote replay reads from a bag reads the same pose back.
  const auto back = logs::detail::decode_pose_cdr(ours);
  EXPECT_EQ(back.frame_id, "map");
  EXPECT_NEAR(back.pose.theta, 0.7, 1e-12);
}

TEST_F(Golden, TfMessage) {
  std::vector<TransformStamped> tf(2);
  tf[0].header = {{1733540001, 5}, "map"};
  tf[0].child_frame_id = "odom";
  tf[0].transform = {0.125, -3.5, -2.9};
  tf[1].header = {{1733540001, 999999999}, "odom"};
  tf[1].child_frame_id = "base_footprint";
  tf[1].transform = {10.0, 20.0, 3.0};
  std::vector<geometry_msgs_msg_dds__TransformStamped_> items(tf.size());
  for (std::size_t k = 0; k < tf.size(); ++k) {
    fill(items[k].header_, tf[k].header);
    items[k].child_frame_id_ = idl_string(tf[k].child_frame_id);
    const auto pose = idl_pose(tf[k].transform);
    items[k].transform_ = {{pose.position_.x_, pose.position_.y_, pose.position_.z_},
                           pose.orientation_};
  }
  tf2_msgs_msg_dds__TFMessage_ s{};
  s.transforms_ = idl_sequence<dds_sequence_geometry_msgs_msg_dds__TransformStamped_>(items);
  CycloneChannel channel(domain(), tf2_msgs_msg_dds__TFMessage__desc);
  const std::string ours = encode_tf(tf);
  expect_same_bytes(ours, channel.serialize(&s));
  channel.decode(ours, [&](const void* p) {
    const auto& d = *static_cast<const tf2_msgs_msg_dds__TFMessage_*>(p);
    ASSERT_EQ(d.transforms_._length, 2U);
    expect_header(d.transforms_._buffer[1].header_, tf[1].header);
    EXPECT_STREQ(d.transforms_._buffer[1].child_frame_id_, "base_footprint");
    EXPECT_EQ(d.transforms_._buffer[0].transform_.translation_.y_, -3.5);
  });
  const auto back = logs::detail::decode_tf_cdr(ours);
  ASSERT_EQ(back.size(), 2U);
  EXPECT_EQ(back[0].child, "odom");
  EXPECT_NEAR(back[0].pose.theta, -2.9, 1e-12);

  tf2_msgs_msg_dds__TFMessage_ none{};
  expect_same_bytes(encode_tf({}), channel.serialize(&none));
}

TEST_F(Golden, ParticleCloud) {
  const Header header{{-3, 250000000}, "map"};
  const std::vector<Particle> particles = {
      {{1.0, 2.0, 0.5}, 0.25}, {{-1.0, 0.0, -3.0}, 0.5}, {{7.0, 8.0, 3.1}, 0.25}};
  std::vector<nav2_msgs_msg_dds__Particle_> items;
  for (const Particle& p : particles) items.push_back({idl_pose(p.pose), p.weight});
  nav2_msgs_msg_dds__ParticleCloud_ s{};
  fill(s.header_, header);
  s.particles_ = idl_sequence<dds_sequence_nav2_msgs_msg_dds__Particle_>(items);
  CycloneChannel channel(domain(), nav2_msgs_msg_dds__ParticleCloud__desc);
  const std::string ours = encode_particle_cloud(header, particles);
  expect_same_bytes(ours, channel.serialize(&s));
  channel.decode(ours, [&](const void* p) {
    const auto& d = *static_cast<const nav2_msgs_msg_dds__ParticleCloud_*>(p);
    expect_header(d.header_, header);
    ASSERT_EQ(d.particles_._length, 3U);
    expect_pose(d.particles_._buffer[2].pose_, particles[2].pose);
    EXPECT_EQ(d.particles_._buffer[1].weight_, 0.5);
  });
  nav2_msgs_msg_dds__ParticleCloud_ empty{};
  fill(empty.header_, header);
  expect_same_bytes(encode_particle_cloud(header, {}), channel.serialize(&empty));
}

TEST_F(Golden, LaserScan) {
  LaserScanMessage msg;
  msg.header = {{1733540002, 42}, "laser"};
  msg.angle_min = -2.0F;
  msg.angle_max = 2.0F;
  msg.angle_increment = 0.5F;
  msg.time_increment = 1e-4F;
  msg.scan_time = 0.025F;
  msg.range_min = 0.1F;
  msg.range_max = 30.0F;
  msg.ranges = {1.0F, 2.5F, NAN, INFINITY, 0.05F, 30.0F, 4.0F, 5.0F, 6.0F};
  msg.intensities = {100.0F, 0.0F, 7.5F};
  sensor_msgs_msg_dds__LaserScan_ s{};
  fill(s.header_, msg.header);
  s.angle_min_ = msg.angle_min;
  s.angle_max_ = msg.angle_max;
  s.angle_increment_ = msg.angle_increment;
  s.time_increment_ = msg.time_increment;
  s.scan_time_ = msg.scan_time;
  s.range_min_ = msg.range_min;
  s.range_max_ = msg.range_max;
  s.ranges_ = idl_sequence<dds_sequence_float>(msg.ranges);
  s.intensities_ = idl_sequence<dds_sequence_float>(msg.intensities);
  CycloneChannel channel(domain(), sensor_msgs_msg_dds__LaserScan__desc);
  const std::string ours = encode_laser_scan(msg);
  expect_same_bytes(ours, channel.serialize(&s));
  channel.decode(ours, [&](const void* p) {
    const auto& d = *static_cast<const sensor_msgs_msg_dds__LaserScan_*>(p);
    expect_header(d.header_, msg.header);
    EXPECT_EQ(d.scan_time_, 0.025F);
    ASSERT_EQ(d.ranges_._length, 9U);
    EXPECT_TRUE(std::isnan(d.ranges_._buffer[2]));
    EXPECT_EQ(d.ranges_._buffer[8], 6.0F);
    ASSERT_EQ(d.intensities_._length, 3U);
    EXPECT_EQ(d.intensities_._buffer[2], 7.5F);
  });
  // mote replay's decoder reads the scan back.
  const auto back = logs::detail::decode_laser_scan_cdr(ours);
  EXPECT_EQ(back.frame_id, "laser");
  EXPECT_EQ(back.scan.ranges.size(), 9U);
  EXPECT_EQ(back.scan.angle_increment, 0.5F);
}

TEST(LaserScanMessage, FromAMoteScan) {
  LaserScan scan;
  scan.stamp = 12.75;
  scan.angle_min = -1.5F;
  scan.angle_increment = 0.25F;
  scan.range_min = 0.2F;
  scan.range_max = 20.0F;
  scan.ranges = {1.0F, 2.0F, 3.0F, 4.0F, 5.0F};
  const LaserScanMessage m = to_laser_scan_message(scan, "front_laser");
  EXPECT_EQ(m.header.stamp, (Stamp{12, 750000000}));
  EXPECT_EQ(m.header.frame_id, "front_laser");
  EXPECT_EQ(m.angle_max, -0.5F);
  EXPECT_EQ(m.ranges, scan.ranges);
  EXPECT_TRUE(m.intensities.empty());
}

TEST_F(Golden, DiagnosticArray) {
  DiagnosticArray msg;
  msg.header = {{1733540003, 7}, ""};
  msg.status.push_back({DiagnosticStatus::kWarn,
                        "mote: localization",
                        "uncertain",
                        "mote",
                        {{"state", "uncertain"}, {"misfit", "0.42"}}});
  msg.status.push_back({DiagnosticStatus::kOk, "mote: scans", "ok", "", {}});
  std::vector<std::vector<diagnostic_msgs_msg_dds__KeyValue_>> values(msg.status.size());
  std::vector<diagnostic_msgs_msg_dds__DiagnosticStatus_> status(msg.status.size());
  for (std::size_t k = 0; k < msg.status.size(); ++k) {
    const DiagnosticStatus& m = msg.status[k];
    for (const KeyValue& kv : m.values)
      values[k].push_back({idl_string(kv.key), idl_string(kv.value)});
    status[k] = {m.level, idl_string(m.name), idl_string(m.message), idl_string(m.hardware_id),
                 idl_sequence<dds_sequence_diagnostic_msgs_msg_dds__KeyValue_>(values[k])};
  }
  diagnostic_msgs_msg_dds__DiagnosticArray_ s{};
  fill(s.header_, msg.header);
  s.status_ = idl_sequence<dds_sequence_diagnostic_msgs_msg_dds__DiagnosticStatus_>(status);
  CycloneChannel channel(domain(), diagnostic_msgs_msg_dds__DiagnosticArray__desc);
  const std::string ours = encode_diagnostics(msg);
  expect_same_bytes(ours, channel.serialize(&s));
  channel.decode(ours, [&](const void* p) {
    const auto& d = *static_cast<const diagnostic_msgs_msg_dds__DiagnosticArray_*>(p);
    ASSERT_EQ(d.status_._length, 2U);
    EXPECT_EQ(d.status_._buffer[0].level_, DiagnosticStatus::kWarn);
    EXPECT_STREQ(d.status_._buffer[0].message_, "uncertain");
    ASSERT_EQ(d.status_._buffer[0].values_._length, 2U);
    EXPECT_STREQ(d.status_._buffer[0].values_._buffer[1].value_, "0.42");
    EXPECT_EQ(d.status_._buffer[1].values_._length, 0U);
  });
}

TEST(Stamp, SplitsSecondsAsRosTimeDoes) {
  EXPECT_EQ(to_stamp(1.5), (Stamp{1, 500000000}));
  EXPECT_EQ(to_stamp(-0.25), (Stamp{-1, 750000000}));
  EXPECT_EQ(to_stamp(2.9999999999), (Stamp{3, 0}));
  EXPECT_EQ(to_stamp(NAN), (Stamp{}));
  EXPECT_EQ(to_stamp(1e12), (Stamp{2147483647, 999999999}));
  EXPECT_EQ(to_stamp(-INFINITY), (Stamp{-2147483647 - 1, 0}));
  EXPECT_DOUBLE_EQ(to_seconds(to_stamp(1733540000.125)), 1733540000.125);
}

}  // namespace
}  // namespace mote::ros::test
