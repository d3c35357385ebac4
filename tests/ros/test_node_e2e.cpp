// mote play and mote node as a user runs them, on a loopback DDS domain of the test's own: the
// node localizes the TurtleBot 4 recording played over DDS, and what it publishes, read back over
// DDS, agrees with `mote replay` on the same recording.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "dds_endpoints.hpp"
#include "loopback_dds.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/ros/messages.hpp"
#include "mote_test/data.hpp"
#include "node_process.hpp"
#include "ros2_messages.hpp"

namespace mote::ros::detail {
namespace {

using mote::ros::testing::Process;
using mote::ros::testing::use_loopback_domain;
using mote_cli_test::json_number;
using mote_cli_test::last_line;
using mote_cli_test::mote;
using mote_cli_test::scratch;
using mote_cli_test::slurp;
using namespace std::chrono_literals;

// The last pose of a TUM trajectory (stamp x y z qx qy qz qw).
Pose2 last_tum_pose(const std::filesystem::path& path) {
  std::istringstream line(last_line(slurp(path)));
  double t = 0.0, x = 0.0, y = 0.0, z = 0.0, qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
  line >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
  return {x, y, 2.0 * std::atan2(qz, qw)};
}

// What the test hears from the node over DDS.
struct Listener {
  explicit Listener(int domain)
      : participant(domain),
        amcl_pose(participant, "/amcl_pose", "geometry_msgs/msg/PoseWithCovarianceStamped",
                  kAmclPoseQos),
        tf(participant, "/tf", "tf2_msgs/msg/TFMessage", kTfQos),
        state(participant, "/localization_state", "diagnostic_msgs/msg/DiagnosticArray",
              kAmclPoseQos) {}

  void drain() {
    for (auto& m : amcl_pose.take()) poses.push_back(logs::detail::decode_pose_cdr(m));
    for (auto& m : tf.take()) {
      for (auto& t : logs::detail::decode_tf_cdr(m)) {
        if (t.parent == "map" && t.child == "odom") map_to_odom.push_back(t);
      }
    }
    states += state.take().size();
  }

  Participant participant;
  RawReader amcl_pose;
  RawReader tf;
  RawReader state;
  std::vector<logs::detail::PoseMessage> poses;
  std::vector<logs::detail::TransformMessage> map_to_odom;
  std::size_t states = 0;
};

void listen_until_exit(Listener& listener, Process& p, std::chrono::seconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    listener.drain();
    if (p.wait(50ms) >= 0) return;
  }
}

TEST(NodeEndToEnd, LocalizesTheTurtleBotRecordingPlayedOverDdsAsReplayDoes) {
  MOTE_REQUIRE_DATA(bag, "ros2/mac_take2");
  MOTE_REQUIRE_DATA(map, "ros2/mac_1st_floor_9_23.yaml");
  const std::string domain = std::to_string(use_loopback_domain());
  const auto dir = scratch("node_e2e");
  const auto replay = mote("replay --map '" + map.string() + "' --log '" + bag.string() +
                           "' --out '" + (dir / "replay").string() + "' --quiet");
  ASSERT_EQ(replay.status, 0) << replay.err;
  const Pose2 replayed = last_tum_pose(dir / "replay" / "trajectory.tum");

  Listener listener(std::stoi(domain));
  const std::string stats = (dir / "stats.json").string();
  const std::string pose_file = (dir / "pose.yaml").string();
  Process node({MOTE_EXE, "node", "--domain", domain, "--stats", stats, "--pose-file", pose_file},
               (dir / "node.log").string());
  ASSERT_TRUE(node.started());
  // The map goes out on /map after the node has started (transient local: it waits for it).
  Process play({MOTE_EXE, "play", bag.string(), "--map", map.string(), "--domain", domain, "--wait",
                "60", "--rate", "1"},
               (dir / "play.log").string());
  listen_until_exit(listener, play, 180s);
  ASSERT_EQ(play.wait(1ms), 0) << slurp(dir / "play.log");
  const auto drain_end = std::chrono::steady_clock::now() + 3s;
  while (std::chrono::steady_clock::now() < drain_end) {
    listener.drain();
    std::this_thread::sleep_for(20ms);
  }
  node.signal(SIGTERM);
  EXPECT_EQ(node.wait(5s), 0) << "the node did not end on SIGTERM: " << slurp(dir / "node.log");
  listener.drain();

  const std::string json = slurp(stats);
  std::cout << "node: " << json << "replay's last pose " << replayed.x << " " << replayed.y << " "
            << replayed.theta << '\n';
  EXPECT_NE(json.find("\"state\": \"tracking\""), std::string::npos) << json;
  EXPECT_GE(json_number(json, "scans_received"), 300) << json;
  EXPECT_EQ(json_number(json, "malformed"), 0) << json;
  ASSERT_FALSE(listener.poses.empty());
  const Pose2 live = listener.poses.back().pose;
  EXPECT_LT(std::hypot(live.x - replayed.x, live.y - replayed.y), 0.10)
      << "node " << live.x << " " << live.y << ", replay " << replayed.x << " " << replayed.y;
  EXPECT_LT(std::abs(wrap_angle(live.theta - replayed.theta)), 0.05);
  ASSERT_FALSE(listener.map_to_odom.empty());
  EXPECT_GE(static_cast<double>(listener.map_to_odom.size()), json_number(json, "published") * 0.9);
  EXPECT_GT(listener.states, 0U);
  // The pose file holds a pose from the tracking stretch, saved every 2 s: within the distance
  // the robot drives in that time of the end.
  const std::string saved = slurp(pose_file);
  std::istringstream fields(saved);
  std::string line;
  double x = NAN, y = NAN;
  while (std::getline(fields, line)) {
    if (line.rfind("x: ", 0) == 0) x = std::stod(line.substr(3));
    if (line.rfind("y: ", 0) == 0) y = std::stod(line.substr(3));
  }
  EXPECT_LT(std::hypot(x - live.x, y - live.y), 1.0) << saved;
}

// The stamped poses of a TUM trajectory.
std::vector<std::pair<double, Pose2>> tum_poses(const std::filesystem::path& path) {
  std::vector<std::pair<double, Pose2>> poses;
  std::istringstream text(slurp(path));
  std::string line;
  while (std::getline(text, line)) {
    std::istringstream f(line);
    double t = 0.0, x = 0.0, y = 0.0, z = 0.0, qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
    if (f >> t >> x >> y >> z >> qx >> qy >> qz >> qw) {
      poses.emplace_back(t, Pose2{x, y, 2.0 * std::atan2(qz, qw)});
    }
  }
  return poses;
}

// The map goes out before the node starts (transient local: the node gets it late), an
// /initialpose arrives mid-run at the pose replay had there, and later the map again: the node
// restarts at the initial pose, then swaps the new map in at its pose of that moment, and ends
// where replay ends.
TEST(NodeEndToEnd, TakesAMapPublishedBeforeItStartedAndAnInitialPoseMidRun) {
  MOTE_REQUIRE_DATA(bag, "ros2/mac_take2");
  MOTE_REQUIRE_DATA(map, "ros2/mac_1st_floor_9_23.yaml");
  const int id = use_loopback_domain();
  const std::string domain = std::to_string(id);
  const auto dir = scratch("node_e2e_late");
  const auto replay = mote("replay --map '" + map.string() + "' --log '" + bag.string() +
                           "' --out '" + (dir / "replay").string() + "' --quiet");
  ASSERT_EQ(replay.status, 0) << replay.err;
  const auto replayed = tum_poses(dir / "replay" / "trajectory.tum");
  ASSERT_GT(replayed.size(), 30U);

  Process play({MOTE_EXE, "play", bag.string(), "--map", map.string(), "--domain", domain, "--wait",
                "60", "--rate", "2"},
               (dir / "play.log").string());
  std::this_thread::sleep_for(2s);  // the map is out, nobody listens yet
  const std::string stats = (dir / "stats.json").string();
  Process node({MOTE_EXE, "node", "--domain", domain, "--stats", stats},
               (dir / "node.log").string());
  // Mid-run, once the node has converged, /initialpose at the pose replay had at that stamp.
  const Participant operator_console(id);
  const RawWriter initial_pose(operator_console, "/initialpose",
                               "geometry_msgs/msg/PoseWithCovarianceStamped", kInitialPoseQos);
  RawReader pose_now(operator_console, "/amcl_pose", "geometry_msgs/msg/PoseWithCovarianceStamped",
                     kAmclPoseQos);
  const RawWriter map_again(operator_console, "/map", "nav_msgs/msg/OccupancyGrid", kMapQos);
  bool sent = false;
  bool map_sent = false;
  const auto end = std::chrono::steady_clock::now() + 120s;
  while (play.wait(20ms) < 0 && std::chrono::steady_clock::now() < end) {
    for (const std::string& m : pose_now.take()) {
      const double t = logs::detail::decode_pose_cdr(m).stamp;
      if (sent && !map_sent && t >= replayed[replayed.size() * 3 / 4].first) {
        map_again.write(encode_occupancy_grid(Header{to_stamp(t), "map"}, load_map(map)));
        map_sent = true;
      }
      if (sent || t < replayed[replayed.size() / 2].first) continue;
      const Pose2 p = replayed[replayed.size() / 2].second;  // close to t: the robot is slow
      PoseWithCovarianceStamped start{.header = {to_stamp(t), "map"}, .pose = p};
      start.covariance = {0.04, 0, 0, 0, 0.04, 0, 0, 0, 0.01};
      initial_pose.write(encode_pose_with_covariance(start));
      sent = true;
    }
  }
  ASSERT_EQ(play.wait(1ms), 0) << slurp(dir / "play.log");
  std::this_thread::sleep_for(2s);
  node.signal(SIGINT);
  EXPECT_EQ(node.wait(5s), 0) << slurp(dir / "node.log");
  const std::string json = slurp(stats);
  std::cout << "node: " << json;
  EXPECT_TRUE(sent);
  EXPECT_TRUE(map_sent);
  EXPECT_EQ(json_number(json, "maps"), 2) << slurp(dir / "node.log");
  EXPECT_NE(slurp(dir / "node.log").find("new map: filter started at the last pose"),
            std::string::npos)
      << slurp(dir / "node.log");
  EXPECT_EQ(json_number(json, "initial_poses"), 1) << slurp(dir / "node.log");
  EXPECT_NE(json.find("\"state\": \"tracking\""), std::string::npos) << json;
  const Pose2 last = replayed.back().second;
  EXPECT_LT(std::hypot(json_number(json, "x") - last.x, json_number(json, "y") - last.y), 0.10)
      << json;
}

}  // namespace
}  // namespace mote::ros::detail
