// mote::ros::Node in the test's process, fed by a participant of the test's own over loopback
// DDS: bad input of every kind is counted and warned about, never fatal, and the node goes on.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "dds_endpoints.hpp"
#include "loopback_dds.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/ros/messages.hpp"
#include "mote/ros/node.hpp"

namespace mote::ros {
namespace {

using detail::RawWriter;
using mote::ros::testing::eventually;
using mote::ros::testing::use_loopback_domain;
using namespace std::chrono_literals;

const std::filesystem::path kFloorplan = MOTE_SOURCE_DIR "/sim/data/floorplan.yaml";

// The robot's side of the graph: a laser on base_link, odometry on /tf.
struct Robot {
  explicit Robot(int domain)
      : participant(domain),
        scan(participant, "/scan", "sensor_msgs/msg/LaserScan", detail::kSensorQos),
        tf(participant, "/tf", "tf2_msgs/msg/TFMessage", detail::kTfQos),
        tf_static(participant, "/tf_static", "tf2_msgs/msg/TFMessage", detail::kTfStaticQos),
        map(participant, "/map", "nav_msgs/msg/OccupancyGrid", detail::kMapQos),
        initial_pose(participant, "/initialpose", "geometry_msgs/msg/PoseWithCovarianceStamped",
                     detail::kInitialPoseQos) {}

  void mount_laser() const {
    const TransformStamped t{{to_stamp(0.0), "base_link"}, "laser", Pose2{0.1, 0.0, 0.0}};
    tf_static.write(encode_tf(std::span(&t, 1)));
  }
  // Odometry at t, then a scan at t from `frame` on `laser` (every beam 2 m: a wall all around).
  void drive(double t, const std::string& frame = "laser", const RawWriter* laser = nullptr) const {
    const TransformStamped odom{{to_stamp(t), "odom"}, "base_link", Pose2{0.2 * t, 0.0, 0.0}};
    tf.write(encode_tf(std::span(&odom, 1)));
    LaserScan s;
    s.stamp = t;
    s.angle_min = -1.5F;
    s.angle_increment = 0.05F;
    s.range_min = 0.1F;
    s.range_max = 10.0F;
    s.ranges.assign(61, 2.0F);
    (laser != nullptr ? *laser : scan).write(encode_laser_scan(to_laser_scan_message(s, frame)));
  }

  detail::Participant participant;
  RawWriter scan;
  RawWriter tf;
  RawWriter tf_static;
  RawWriter map;
  RawWriter initial_pose;
};

// What the node printed, for the tests that check its words.
struct Lines {
  std::function<void(const std::string&)> sink() {
    return [this](const std::string& line) {
      const std::lock_guard lock(mutex);
      text += line + "\n";
    };
  }
  [[nodiscard]] bool has(const std::string& words) const {
    const std::lock_guard lock(mutex);
    return text.find(words) != std::string::npos;
  }
  [[nodiscard]] std::string copy() const {
    const std::lock_guard lock(mutex);
    return text;
  }
  mutable std::mutex mutex;
  std::string text;
};

NodeOptions options(int domain, Lines& lines) {
  NodeOptions o;
  o.domain_id = domain;
  o.config.max_particles = 5000;
  o.config.threads = 1;
  o.log = lines.sink();
  return o;
}

void drive_until(const Robot& robot, Node& node,
                 const std::function<bool(const NodeCounters&)>& done, double& t,
                 const std::string& frame = "laser", std::chrono::milliseconds timeout = 20s) {
  EXPECT_TRUE(eventually(
      [&] {
        robot.drive(t += 0.1, frame);
        std::this_thread::sleep_for(5ms);
        return done(node.counters());
      },
      timeout));
}

TEST(Node, MalformedSamplesOnEveryTopicAreCountedAndTheNodeGoesOn) {
  const int domain = use_loopback_domain();
  Lines lines;
  NodeOptions o = options(domain, lines);
  o.map_file = kFloorplan;
  Node node(std::move(o));
  const Robot robot(domain);
  ASSERT_TRUE(eventually([&] { return robot.scan.matched() == 1 && robot.map.matched() == 1; }));
  const std::string garbage("\x00\x01\x00\x00\xff\xff\xff\x7f", 8);  // a string of 2^31 bytes
  for (const RawWriter* w :
       {&robot.scan, &robot.tf, &robot.tf_static, &robot.map, &robot.initial_pose}) {
    w->write(garbage);
  }
  ASSERT_TRUE(eventually([&] { return node.counters().malformed == 5; }))
      << node.counters().malformed << "\n"
      << lines.text;
  EXPECT_TRUE(lines.has("malformed scan on /scan"));
  EXPECT_TRUE(lines.has("map on /map refused"));
  robot.mount_laser();
  double t = 0.0;
  drive_until(
      robot, node, [](const NodeCounters& c) { return c.updates >= 1; }, t);
  EXPECT_EQ(node.counters().malformed, 5U);
}

TEST(Node, AMapOfZeroSizeOrAbsurdSizeAndANanInitialPoseAreRefused) {
  const int domain = use_loopback_domain();
  Lines lines;
  NodeOptions o = options(domain, lines);
  o.map_file = kFloorplan;
  Node node(std::move(o));
  const Robot robot(domain);
  ASSERT_TRUE(eventually([&] { return robot.map.matched() == 1 && node.counters().maps == 1; }));
  // A 1 x 1 map whose header then claims 100000 x 100000 cells: refused before allocating.
  const OccupancyGrid one(1, 1, 0.05, Pose2{}, {CellState::kFree});
  std::string huge = encode_occupancy_grid(Header{to_stamp(1.0), "map"}, one);
  const std::size_t at = huge.find(std::string("\x01\x00\x00\x00\x01\x00\x00\x00", 8));
  ASSERT_NE(at, std::string::npos);
  huge.replace(at, 8, std::string("\xa0\x86\x01\x00\xa0\x86\x01\x00", 8));
  // /map keeps the last sample only: one at a time.
  robot.map.write(huge);
  ASSERT_TRUE(eventually([&] { return node.counters().malformed == 1; })) << lines.text;
  EXPECT_TRUE(lines.has("100000 x 100000")) << lines.text;
  std::string empty = encode_occupancy_grid(Header{to_stamp(1.0), "map"}, one);
  empty.replace(at, 8, std::string(8, '\0'));
  robot.map.write(empty);
  ASSERT_TRUE(eventually([&] { return node.counters().malformed == 2; })) << lines.text;
  PoseWithCovarianceStamped nan{.header = {to_stamp(1.0), "map"},
                                .pose = Pose2{std::numeric_limits<double>::quiet_NaN(), 0, 0}};
  robot.initial_pose.write(encode_pose_with_covariance(nan));
  ASSERT_TRUE(eventually([&] { return node.counters().malformed == 3; })) << lines.text;
  EXPECT_EQ(node.counters().initial_poses, 0U);
  EXPECT_TRUE(lines.has("initial pose refused"));
  EXPECT_EQ(node.counters().maps, 1U);  // the file's, kept
}

TEST(Node, AScanWhoseFrameHasNoTransformIsDroppedAndNamed) {
  const int domain = use_loopback_domain();
  Lines lines;
  NodeOptions o = options(domain, lines);
  o.map_file = kFloorplan;
  Node node(std::move(o));
  const Robot robot(domain);
  robot.mount_laser();
  ASSERT_TRUE(eventually([&] { return robot.scan.matched() == 1; }));
  double t = 0.0;
  drive_until(
      robot, node, [](const NodeCounters& c) { return c.dropped_no_transform >= 3; }, t,
      "front_laser");
  EXPECT_EQ(node.counters().updates, 0U);
  EXPECT_TRUE(lines.has("to the scan's frame 'front_laser'")) << lines.text;
}

TEST(Node, ScansBeforeAnyMapAreCountedAndTheWarningSaysNoMapYet) {
  const int domain = use_loopback_domain();
  Lines lines;
  Node node(options(domain, lines));
  const Robot robot(domain);
  robot.mount_laser();
  ASSERT_TRUE(eventually([&] { return robot.scan.matched() == 1; }));
  double t = 0.0;
  drive_until(
      robot, node, [](const NodeCounters& c) { return c.dropped_no_map >= 3; }, t);
  ASSERT_TRUE(eventually([&] { return lines.has("no map yet"); }, 15s)) << lines.text;
  // The map arrives on the topic: the node starts and updates.
  robot.map.write(encode_occupancy_grid(Header{to_stamp(t), "map"}, load_map(kFloorplan)));
  drive_until(
      robot, node, [](const NodeCounters& c) { return c.updates >= 1; }, t);
  EXPECT_EQ(node.counters().maps, 1U);
}

TEST(Node, FirstMapOnlyKeepsTheFirstMapAndSaysSo) {
  const int domain = use_loopback_domain();
  Lines lines;
  NodeOptions o = options(domain, lines);
  o.map_file = kFloorplan;
  o.first_map_only = true;
  Node node(std::move(o));
  const Robot robot(domain);
  ASSERT_TRUE(eventually([&] { return robot.map.matched() == 1 && node.counters().maps == 1; }));
  robot.map.write(encode_occupancy_grid(Header{to_stamp(1.0), "map"}, load_map(kFloorplan)));
  ASSERT_TRUE(eventually([&] { return lines.has("first_map_only keeps the first one"); }))
      << lines.text;
  EXPECT_EQ(node.counters().maps, 1U);
}

// A map whose preparation takes a while: 7000 x 7000 cells of 5 cm, walls on the border.
OccupancyGrid big_room() {
  constexpr std::size_t kSide = 7000;
  std::vector<CellState> cells(kSide * kSide, CellState::kFree);
  for (std::size_t k = 0; k < kSide; ++k) {
    for (const std::size_t cell : {k, k * kSide, (kSide - 1) * kSide + k, k * kSide + kSide - 1}) {
      cells[cell] = CellState::kOccupied;
    }
  }
  constexpr int side = static_cast<int>(kSide);
  return {side, side, 0.05, Pose2{}, std::move(cells)};
}

// A map that arrives while another is prepared waits for the map builder, and the receive
// thread goes on taking scans meanwhile (it used to wait for the builder with it); then the
// newer map is prepared and swapped in.
TEST(Node, AMapArrivingWhileAnotherIsPreparedWaitsAndTheScansGoOn) {
  const int domain = use_loopback_domain();
  Lines lines;
  Node node(options(domain, lines));
  const Robot robot(domain);
  robot.mount_laser();
  ASSERT_TRUE(eventually([&] { return robot.map.matched() == 1 && robot.scan.matched() == 1; }));
  robot.map.write(encode_occupancy_grid(Header{to_stamp(0.0), "map"}, big_room()));
  // Both the writer and the node keep the last map only: a second map written before the node
  // took the big one replaces it on the wire (a loaded CI machine took longer than 100 ms).
  ASSERT_TRUE(eventually([&] { return node.counters().map_messages == 1; }, 60s)) << lines.copy();
  ASSERT_EQ(node.counters().maps, 0U) << "the big map was ready too soon for this test";
  robot.map.write(encode_occupancy_grid(Header{to_stamp(0.1), "map"}, load_map(kFloorplan)));
  double t = 0.0;
  std::uint64_t scans_before_any_map = 0;
  drive_until(
      robot, node,
      [&](const NodeCounters& c) {
        if (c.maps == 0) scans_before_any_map = c.scans_received;
        return c.maps == 2 && c.updates >= 1;
      },
      // 0.7 s for the big map in Release; under AddressSanitizer it took over 20 s.
      t, "laser", 180s);
  EXPECT_GE(scans_before_any_map, 3U) << "no scan was taken while the big map was prepared";
  const std::string said = lines.copy();
  const std::size_t big = said.find("map from /map: 7000 x 7000 cells");
  ASSERT_NE(big, std::string::npos) << said;
  EXPECT_NE(said.find("map from /map: ", big + 1), std::string::npos)
      << "the second map was not prepared after the first\n"
      << said;
}

TEST(Node, ASecondLaserOnATopicOfItsOwnUpdatesWithItsOwnMounting) {
  const int domain = use_loopback_domain();
  Lines lines;
  NodeOptions o = options(domain, lines);
  o.map_file = kFloorplan;
  o.scan_topics = {"front/scan", "rear/scan"};
  Node node(std::move(o));
  const Robot robot(domain);
  const RawWriter rear(robot.participant, "/rear/scan", "sensor_msgs/msg/LaserScan",
                       detail::kSensorQos);
  const TransformStamped mount{{to_stamp(0.0), "base_link"}, "rear_laser", Pose2{-0.2, 0, 3.1}};
  robot.tf_static.write(encode_tf(std::span(&mount, 1)));
  ASSERT_TRUE(eventually([&] { return rear.matched() == 1; }));
  double t = 0.0;
  ASSERT_TRUE(eventually([&] {
    robot.drive(t += 0.1, "rear_laser", &rear);
    std::this_thread::sleep_for(5ms);
    return node.counters().updates >= 2;
  })) << lines.text;
  EXPECT_EQ(node.counters().dropped_no_transform, 0U);
}

TEST(Node, AnInitialPoseRestartsTheFilterThereAndStopEndsWithinASecond) {
  const int domain = use_loopback_domain();
  Lines lines;
  NodeOptions o = options(domain, lines);
  o.map_file = kFloorplan;
  Node node(std::move(o));
  const Robot robot(domain);
  robot.mount_laser();
  ASSERT_TRUE(eventually([&] { return robot.initial_pose.matched() == 1; }));
  double t = 0.0;
  drive_until(
      robot, node, [](const NodeCounters& c) { return c.updates >= 1; }, t);
  PoseWithCovarianceStamped start{.header = {to_stamp(t), "map"}, .pose = Pose2{3.0, 4.0, 0.5}};
  start.covariance = {0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.001};
  robot.initial_pose.write(encode_pose_with_covariance(start));
  ASSERT_TRUE(eventually([&] { return node.counters().initial_poses == 1; }));
  node.request_nomotion_update();
  const std::uint64_t before = node.counters().updates;
  drive_until(
      robot, node, [&](const NodeCounters& c) { return c.updates > before; }, t);
  const Pose2 p = node.counters().pose;
  EXPECT_LT(std::hypot(p.x - 3.0, p.y - 4.0), 0.5) << p.x << " " << p.y;
  EXPECT_TRUE(lines.has("initialized at /initialpose"));
  const auto start_stop = std::chrono::steady_clock::now();
  node.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start_stop, 1s);
  EXPECT_GE(node.counters().updates, before + 1);  // the final counts stay readable
}

}  // namespace
}  // namespace mote::ros
