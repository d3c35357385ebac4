#include <gtest/gtest.h>

#include "mote/core/error.hpp"
#include "mote/ros/ros_names.hpp"

namespace mote::ros {
namespace {

TEST(RosNames, TopicsGetTheRtPrefix) {
  EXPECT_EQ(dds_topic_name("/scan"), "rt/scan");
  EXPECT_EQ(dds_topic_name("scan"), "rt/scan");
  EXPECT_EQ(dds_topic_name("/robot1/tf_static"), "rt/robot1/tf_static");
}

TEST(RosNames, BadTopicsAreRefused) {
  EXPECT_THROW((void)dds_topic_name(""), InputError);
  EXPECT_THROW((void)dds_topic_name("/scan/"), InputError);
  EXPECT_THROW((void)dds_topic_name("/a//b"), InputError);
  EXPECT_THROW((void)dds_topic_name("/sc an"), InputError);
}

TEST(RosNames, TypesGetTheDdsModule) {
  EXPECT_EQ(dds_type_name("sensor_msgs/msg/LaserScan"), "sensor_msgs::msg::dds_::LaserScan_");
  EXPECT_EQ(dds_type_name("nav2_msgs/msg/ParticleCloud"), "nav2_msgs::msg::dds_::ParticleCloud_");
  EXPECT_THROW((void)dds_type_name("LaserScan"), InputError);
  EXPECT_THROW((void)dds_type_name("sensor_msgs/srv/LaserScan"), InputError);
  EXPECT_THROW((void)dds_type_name("sensor_msgs/msg/"), InputError);
}

}  // namespace
}  // namespace mote::ros
