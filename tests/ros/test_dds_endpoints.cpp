#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dds_endpoints.hpp"
#include "loopback_dds.hpp"
#include "mote/core/error.hpp"

namespace mote::ros::detail {
namespace {

using mote::ros::testing::eventually;
using mote::ros::testing::use_loopback_domain;

// Bytes of a std_msgs/msg/String "hi": header 00 01 00 00, length 3 (with the NUL), "hi\0",
// padded to 4.
const std::string kHello("\x00\x01\x00\x00\x03\x00\x00\x00hi\x00\x00", 12);

// What `reader` takes until the first message has come (empty after the tests' timeout).
std::vector<std::string> first_messages(const RawReader& reader) {
  std::vector<std::string> got;
  (void)eventually([&] {
    for (auto& m : reader.take()) got.push_back(std::move(m));
    return !got.empty();
  });
  return got;
}

TEST(DdsEndpoints, BytesCrossBetweenTwoParticipantsUnchanged) {
  const int domain = use_loopback_domain();
  const Participant a(domain);
  const Participant b(domain);
  const RawWriter writer(a, "/chatter", "std_msgs/msg/String", kDefaultQos);
  const RawReader reader(b, "/chatter", "std_msgs/msg/String", kDefaultQos);
  ASSERT_TRUE(eventually([&] { return writer.matched() == 1 && reader.matched() == 1; }));
  writer.write(kHello);
  const std::vector<std::string> got = first_messages(reader);
  ASSERT_FALSE(got.empty());
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0], kHello);
}

TEST(DdsEndpoints, ALargeMessageIsReassembledFromItsFragments) {
  const int domain = use_loopback_domain();
  const Participant a(domain);
  const Participant b(domain);
  const RawWriter writer(a, "/map", "nav_msgs/msg/OccupancyGrid", kMapQos);
  const RawReader reader(b, "/map", "nav_msgs/msg/OccupancyGrid", kMapQos);
  ASSERT_TRUE(eventually([&] { return writer.matched() == 1; }));
  std::string big(std::string("\x00\x01\x00\x00", 4) + std::string(300000, '\0'));
  for (std::size_t k = 4; k < big.size(); ++k) big[k] = static_cast<char>(k * 7919 % 251);
  writer.write(big);
  const std::vector<std::string> got = first_messages(reader);
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got.at(0), big);
}

TEST(DdsEndpoints, ALateReaderOfATransientLocalTopicGetsTheLastMessage) {
  const int domain = use_loopback_domain();
  const Participant a(domain);
  const RawWriter writer(a, "/map", "nav_msgs/msg/OccupancyGrid", kMapQos);
  writer.write(std::string("\x00\x01\x00\x00old!", 8));
  writer.write(kHello);
  const Participant b(domain);
  const RawReader reader(b, "/map", "nav_msgs/msg/OccupancyGrid", kMapQos);
  const std::vector<std::string> got = first_messages(reader);
  ASSERT_FALSE(got.empty());
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0], kHello);
}

TEST(DdsEndpoints, TopicsOfOtherTypesDoNotMatch) {
  const int domain = use_loopback_domain();
  const Participant a(domain);
  const RawWriter writer(a, "/scan", "sensor_msgs/msg/LaserScan", kSensorQos);
  const RawReader reader(a, "/scan2", "sensor_msgs/msg/LaserScan", kSensorQos);
  const RawReader other(a, "/scan", "sensor_msgs/msg/PointCloud2", kSensorQos);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(writer.matched(), 0U);
}

TEST(DdsEndpoints, ABadDomainIdIsAClearError) {
  setenv("ROS_DOMAIN_ID", "300", 1);
  EXPECT_THROW((void)ros_domain_id(), ConfigError);
  setenv("ROS_DOMAIN_ID", "7", 1);
  EXPECT_EQ(ros_domain_id(), 7);
  unsetenv("ROS_DOMAIN_ID");
  EXPECT_EQ(ros_domain_id(), 0);
}

}  // namespace
}  // namespace mote::ros::detail
