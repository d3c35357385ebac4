// `mote info LOG`: what a recorded log holds (replay/include/mote/replay/log_info.hpp).
#include <array>
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "mote/replay/log_info.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 4> kFlags{{
    {"scan-topic", "TOPIC", "ROS bags: the LaserScan topic (default: the only one)"},
    {"odom-topic", "TOPIC", "ROS bags: the Odometry topic (default: the only one, or tf)"},
    {"odom-frame", "FRAME", "ROS bags: odometry frame when odometry comes from tf (default odom)"},
    {"base-frame", "FRAME", "ROS bags: robot base frame (default: the odometry's child frame)"},
}};

constexpr std::string_view kUsage = "mote info LOG [flags]";
constexpr std::string_view kAbout =
    "Prints what a recorded log holds: format, storage and compression, duration, message\n"
    "counts per topic and type, the laser (beams, field of view, range limits, mounting pose)\n"
    "and the tf frames. LOG: CARMEN .clf/.log, ROS 1 .bag, rosbag2 folder, .mcap or .db3.";

}  // namespace

int info_command(std::span<char* const> words) {
  if (words.empty() || std::string_view(words[0]).starts_with("--")) {
    const ParsedArgs args = parse_args("info", words, kFlags);
    if (args.has("help")) {
      print_help(std::cout, kUsage, kAbout, kFlags);
      return 0;
    }
    throw UsageError("mote info: expects a LOG (see mote info --help)");
  }
  const ParsedArgs args = parse_args("info", words.subspan(1), kFlags);
  replay::ReaderOptions options;
  if (auto t = args.text("scan-topic")) options.scan_topic = *t;
  if (auto t = args.text("odom-topic")) options.odom_topic = *t;
  if (auto f = args.text("odom-frame")) options.odom_frame = *f;
  if (auto f = args.text("base-frame")) options.base_frame = *f;
  replay::print_log_info(std::cout, replay::describe_log(words[0], options));
  return 0;
}

}  // namespace mote::tool
