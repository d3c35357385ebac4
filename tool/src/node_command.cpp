// `mote node`: the live localizer on a ROS 2 graph, until SIGINT or SIGTERM.
#include <array>
#include <chrono>
#include <fstream>
#include <iostream>
#include <thread>

#include "args.hpp"
#include "commands.hpp"
#include "mote/core/error.hpp"
#include "mote/ros/node.hpp"
#include "node_options.hpp"
#include "signals.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 21> kFlags{{
    {"config", "PARAMS.yaml",
     "nav2 params file as it is (its amcl section: frames, topics, laser, robot, particle bounds, "
     "initial pose apply as written; noise and mixture values start mote's adaptive ones) or a "
     "flat mote config"},
    {"nav2-defaults", "", "nav2_amcl's fixed algorithm instead of mote's adaptive one"},
    {"map", "MAP.yaml", "map_server map to use instead of the map topic (default: the topic)"},
    {"scan-topic", "TOPICS", "laser scan topic, or several separated by commas (default scan)"},
    {"map-topic", "TOPIC", "nav_msgs/OccupancyGrid topic (default map)"},
    {"initial-pose", "X,Y,YAW", "start around this pose (m, m, rad) instead of globally"},
    {"pose-file", "FILE",
     "keep the last pose while tracking in FILE (written atomically) and start from it"},
    {"save-pose-rate", "HZ", "how often the pose file is written (default 0.5)"},
    {"base-frame", "FRAME", "robot base frame (default: the child of the odometry frame on /tf)"},
    {"odom-frame", "FRAME", "odometry frame (default odom)"},
    {"global-frame", "FRAME", "map frame (default map)"},
    {"transform-tolerance", "S", "s map -> odom is post-dated by (default 1.0)"},
    {"no-tf", "", "do not publish map -> odom (nav2's tf_broadcast: false)"},
    {"domain", "ID", "DDS domain (default: ROS_DOMAIN_ID, else 0)"},
    {"threads", "N", "filter threads, 0 = every core (default 0)"},
    {"model", "NAME", "likelihood_field or beam (default likelihood_field)"},
    {"max-particles", "N", "KLD upper bound and size of the global set (default 500000)"},
    {"particles", "N", "fixed particle count: min = max = N"},
    {"duration", "S", "end after S seconds (default: run until SIGINT or SIGTERM)"},
    {"stats", "FILE", "at the end, write the counters as JSON to FILE"},
    {"quiet", "", "no summary at the end"},
}};

constexpr std::string_view kUsage =
    "mote node [--config nav2_params.yaml] [--map MAP.yaml] [flags]";
constexpr std::string_view kAbout =
    "Localizes live on a ROS 2 graph over DDS, with no ROS installed: subscribes to the scans,\n"
    "/map, /tf, /tf_static and /initialpose; publishes map -> odom on /tf, /amcl_pose,\n"
    "/particle_cloud and the localization state (/localization_state, /diagnostics). Without a\n"
    "start pose it localizes globally. SIGUSR1 re-initializes globally, SIGUSR2 runs the next\n"
    "update without motion; SIGINT or SIGTERM end it. Discovery follows CYCLONEDDS_URI.";

void write_stats(const std::string& path, const ros::NodeCounters& c) {
  std::ofstream out(path);
  out << "{\"scans_received\": " << c.scans_received
      << ", \"scans_processed\": " << c.scans_processed << ", \"updates\": " << c.updates
      << ", \"scans_skipped\": " << c.scans_skipped
      << ", \"dropped_no_transform\": " << c.dropped_no_transform
      << ", \"dropped_no_odometry\": " << c.dropped_no_odometry
      << ", \"dropped_no_map\": " << c.dropped_no_map << ", \"malformed\": " << c.malformed
      << ", \"map_messages\": " << c.map_messages << ", \"maps\": " << c.maps
      << ", \"initial_poses\": " << c.initial_poses << ", \"published\": " << c.published
      << ", \"state\": \"" << name_of(c.state) << "\", \"misfit\": " << c.misfit
      << ", \"x\": " << c.pose.x << ", \"y\": " << c.pose.y << ", \"yaw\": " << c.pose.theta
      << ", \"stamp\": " << std::fixed << c.pose_stamp
      << ", \"latency_p50_ms\": " << c.latency_p50_ms
      << ", \"latency_p99_ms\": " << c.latency_p99_ms
      << ", \"processing_p50_ms\": " << c.processing_p50_ms
      << ", \"processing_p99_ms\": " << c.processing_p99_ms << "}\n";
  if (!out) throw Error("cannot write " + path);
}

void print_summary(const ros::NodeCounters& c) {
  std::cout << "mote node: " << c.scans_received << " scans received, " << c.updates << " updates, "
            << c.scans_skipped << " skipped (a newer scan arrived), "
            << c.dropped_no_transform + c.dropped_no_odometry + c.dropped_no_map << " dropped, "
            << c.malformed << " malformed\n"
            << "  state " << name_of(c.state) << ", pose " << c.pose.x << " " << c.pose.y << " "
            << c.pose.theta << "\n  scan to map -> odom: p50 " << c.latency_p50_ms << " ms, p99 "
            << c.latency_p99_ms << " ms (of which the node's own: p50 " << c.processing_p50_ms
            << " ms, p99 " << c.processing_p99_ms << " ms)\n";
}

}  // namespace

int node_command(std::span<char* const> words) {
  const ParsedArgs args = parse_args("node", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  ros::NodeOptions options = node_options(args);
  const double duration = args.real("duration", 0.0, 1e9).value_or(0.0);
  install_signal_flags();
  ros::Node node(std::move(options));
  const auto start = std::chrono::steady_clock::now();
  while (!stop_signalled()) {
    if (take_usr1()) node.request_global_localization();
    if (take_usr2()) node.request_nomotion_update();
    if (duration > 0.0 &&
        std::chrono::steady_clock::now() - start > std::chrono::duration<double>(duration)) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  node.stop();
  const ros::NodeCounters c = node.counters();
  if (auto path = args.text("stats")) write_stats(*path, c);
  if (!args.has("quiet")) print_summary(c);
  return 0;
}

}  // namespace mote::tool
