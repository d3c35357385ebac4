// `mote play`: a recorded log and a map published over DDS as ROS 2 topics.
#include <array>
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "mote/ros/dds_domain.hpp"
#include "mote/ros/play.hpp"
#include "signals.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 8> kFlags{{
    {"map", "MAP.yaml", "map_server map published on the map topic (transient local)"},
    {"map-topic", "TOPIC", "topic of the map (default map)"},
    {"rate", "R",
     "playback speed: 1 recorded rate, 2 twice as fast, 0 as fast as possible "
     "(default 1)"},
    {"wait", "S", "s to wait for a subscriber on the scan topic before starting (default 0)"},
    {"linger", "S", "s to keep publishing the map to late subscribers after the end (default 0)"},
    {"domain", "ID", "DDS domain (default: ROS_DOMAIN_ID, else 0)"},
    {"laser-max-range", "M", "m, CARMEN FLASER logs: the no-return reading (default: inferred)"},
    {"quiet", "", "no summary at the end"},
}};

constexpr std::string_view kUsage = "mote play LOG [--map MAP.yaml] [--rate R] [flags]";
constexpr std::string_view kAbout =
    "Publishes a recorded log over DDS as ROS 2 topics, with no ROS installed: a ROS 2 recording\n"
    "(rosbag2 folder, .mcap or .db3) message for message with its bytes unchanged and each\n"
    "topic's QoS as nav2 expects it; a CARMEN log as a robot would (/scan, odom -> base_link on\n"
    "/tf, base_link -> laser on /tf_static). Discovery follows CYCLONEDDS_URI.";

}  // namespace

int play_command(std::span<char* const> words) {
  if (!words.empty() && words[0][0] != '-') {
    const ParsedArgs args = parse_args("play", words.subspan(1), kFlags);
    if (args.has("help")) {
      print_help(std::cout, kUsage, kAbout, kFlags);
      return 0;
    }
    ros::PlayOptions o;
    o.log = words[0];
    if (auto m = args.text("map")) o.map = *m;
    if (auto t = args.text("map-topic")) o.map_topic = *t;
    o.rate = args.real("rate", 0.0, 1e6).value_or(1.0);
    o.wait_for_readers = args.real("wait", 0.0, 3600.0).value_or(0.0);
    o.linger = args.real("linger", 0.0, 1e6).value_or(0.0);
    o.domain_id = static_cast<int>(args.integer("domain", 0, 232).value_or(ros::ros_domain_id()));
    if (auto m = args.real("laser-max-range", 0.01, 1e6)) {
      o.reader.carmen_max_range = static_cast<float>(*m);
    }
    install_signal_flags();
    o.stop_requested = [] { return stop_signalled(); };
    const ros::PlayResult r = ros::play(o);
    if (!args.has("quiet")) {
      std::cout << "mote play: " << (r.stopped ? "stopped after " : "published ") << r.wall_s
                << " s (" << r.recorded_s << " s recorded)\n";
      for (const auto& [topic, n] : r.messages) std::cout << "  " << topic << "  " << n << '\n';
    }
    return 0;
  }
  const ParsedArgs args = parse_args("play", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  throw UsageError("mote play: the log comes first: " + std::string(kUsage));
}

}  // namespace mote::tool
