// The live node's parameters from a nav2 params file (issue 46): nav2_amcl's names and defaults.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mote/core/error.hpp"
#include "mote/engine/node_params.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const std::string kRos = "amcl:\n  ros__parameters:\n";

// nav2_amcl's defaults, as amcl_node.cpp's initParameters declares them.
TEST(NodeParams, DefaultsAreNav2Amcls) {
  const NodeParams p;
  EXPECT_EQ(p.global_frame_id, "map");
  EXPECT_EQ(p.odom_frame_id, "odom");
  EXPECT_EQ(p.base_frame_id, "base_footprint");
  EXPECT_THAT(p.scan_topics, ElementsAre("scan"));
  EXPECT_EQ(p.map_topic, "map");
  EXPECT_DOUBLE_EQ(p.transform_tolerance, 1.0);
  EXPECT_TRUE(p.tf_broadcast);
  EXPECT_FALSE(p.set_initial_pose);
  EXPECT_TRUE(p.initial_pose == InitialPoseParams{});
  EXPECT_FALSE(p.always_reset_initial_pose);
  EXPECT_FALSE(p.first_map_only);
  EXPECT_DOUBLE_EQ(p.save_pose_rate, 0.5);
  EXPECT_FALSE(p.initialize_at_saved_pose);
  EXPECT_EQ(p.saved_pose_filepath, "/tmp/amcl_saved_pose");
  // A file that names none of the node's keys keeps them all.
  EXPECT_TRUE(parse_node_params(kRos + "    alpha1: 0.3\n", "a.yaml") == NodeParams{});
}

TEST(NodeParams, ReadsTheShippedNav2File) {
  const NodeParams p = read_node_params(test::project_test_data() / "nav2_params.yaml");
  EXPECT_TRUE(p == NodeParams{}) << "the shipped file holds nav2's defaults";
}

TEST(NodeParams, ReadsEveryKeyAsWritten) {
  const NodeParams p = parse_node_params(
      kRos +
          "    global_frame_id: world\n    odom_frame_id: wheel_odom\n"
          "    base_frame_id: base_link\n    scan_topic: /front/scan\n    map_topic: /floor\n"
          "    transform_tolerance: 0.2\n    tf_broadcast: false\n    set_initial_pose: true\n"
          "    initial_pose:\n      x: 1.5\n      y: -2.0\n      z: 0.1\n      yaw: 0.7\n"
          "    always_reset_initial_pose: true\n    first_map_only: true\n"
          "    save_pose_rate: 2.0\n    initialize_at_saved_pose: true\n"
          "    saved_pose_filepath: /var/lib/robot/pose\n    alpha1: 0.1\n",
      "robot.yaml");
  EXPECT_EQ(p.global_frame_id, "world");
  EXPECT_EQ(p.odom_frame_id, "wheel_odom");
  EXPECT_EQ(p.base_frame_id, "base_link");
  EXPECT_THAT(p.scan_topics, ElementsAre("/front/scan"));
  EXPECT_EQ(p.map_topic, "/floor");
  EXPECT_DOUBLE_EQ(p.transform_tolerance, 0.2);
  EXPECT_FALSE(p.tf_broadcast);
  EXPECT_TRUE(p.set_initial_pose);
  EXPECT_TRUE((p.initial_pose == InitialPoseParams{1.5, -2.0, 0.1, 0.7}));
  EXPECT_TRUE(p.always_reset_initial_pose);
  EXPECT_TRUE(p.first_map_only);
  EXPECT_DOUBLE_EQ(p.save_pose_rate, 2.0);
  EXPECT_TRUE(p.initialize_at_saved_pose);
  EXPECT_EQ(p.saved_pose_filepath, "/var/lib/robot/pose");
}

// ROS 2 params files may flatten nested names with dots; a flat mote file holds the same keys.
TEST(NodeParams, DottedInitialPoseAndFlatFiles) {
  const NodeParams p = parse_node_params(
      "set_initial_pose: true\ninitial_pose.x: 3.0\ninitial_pose.yaw: -1.0\n"
      "scan_topic: [front/scan, rear/scan]\n",
      "flat.yaml");
  EXPECT_TRUE((p.initial_pose == InitialPoseParams{3.0, 0.0, 0.0, -1.0}));
  EXPECT_THAT(p.scan_topics, ElementsAre("front/scan", "rear/scan")) << "one laser per topic";
}

void expect_error(const std::string& text, const std::string& fragment) {
  try {
    (void)parse_node_params(text, "bad.yaml");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.yaml");
    EXPECT_THAT(e.what(), HasSubstr(fragment)) << text;
  }
}

TEST(NodeParams, BadValuesNameTheKeyAndLine) {
  expect_error(kRos + "    transform_tolerance: -0.5\n",
               "line 3, key 'transform_tolerance': expected a time >= 0 in seconds");
  expect_error("tf_broadcast: sometimes\n", "key 'tf_broadcast': expected true or false");
  expect_error("base_frame_id: \"\"\n", "key 'base_frame_id': expected a non-empty name");
  expect_error("scan_topic: []\n", "key 'scan_topic': expected a topic name or a list");
  expect_error("initial_pose: {x: 1.0, w: 2.0}\n", "key 'initial_pose': expected a map of x, y");
  expect_error("initial_pose: 3\n", "key 'initial_pose'");
  expect_error("initial_pose.yaw: .nan\n", "key 'initial_pose.yaw': expected a finite number");
  expect_error("save_pose_rate: .inf\n", "key 'save_pose_rate'");
  expect_error("- a\n- list\n", "expected a map of parameters");
  EXPECT_THROW((void)read_node_params("/nonexistent/nav2_params.yaml"), InputError);
}

}  // namespace
}  // namespace mote
