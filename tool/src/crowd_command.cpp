// `mote crowd`: a recorded log with people standing around the robot for a stretch.
#include <array>
#include <cstdint>
#include <iomanip>
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "mote/sim/crowd.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 9> kFlags{{
    {"log", "LOG", "recorded log: CARMEN .clf/.log or ROS 1 .bag (required)"},
    {"out", "DIR", "output folder for crowd.clf, created if missing (required)"},
    {"seconds", "S", "how long the crowd stays, s (default 20)"},
    {"start", "STAMP",
     "stamp of the first crowded scan, s (default: the window of S seconds "
     "that turns the most while travelling under 1 m)"},
    {"people", "N", "people in the ring around the robot (default 8)"},
    {"near", "M", "ring's inner distance from the robot, m (default 0.4)"},
    {"far", "M", "ring's outer distance from the robot, m (default 1.0)"},
    {"seed", "N", "draws the people's bearings and distances (default 1)"},
    {"lenient", "", "skip malformed log records instead of failing"},
}};

constexpr std::string_view kUsage =
    "mote crowd --log LOG --out DIR [--seconds S] [--start STAMP] [--people N] [--near M]\n"
    "           [--far M] [--seed N]";
constexpr std::string_view kAbout =
    "Writes DIR/crowd.clf: the log with a ring of people (0.2 m radius each) standing still\n"
    "around the robot for S seconds, shortening every beam that hits one. Odometry, stamps and\n"
    "every other reading stay as recorded, so the log's reference poses still apply:\n"
    "`mote replay --log DIR/crowd.clf --reference REF.tum` tests riding out a crowd.";

sim::CrowdOptions crowd_options(const ParsedArgs& args) {
  sim::CrowdOptions o;
  if (auto v = args.real("seconds", 0.0, 1e6)) o.seconds = *v;
  if (auto v = args.real("start", -1e12, 1e12)) o.start = *v;
  if (auto v = args.integer("people", 1, 1000)) o.people = static_cast<int>(*v);
  if (auto v = args.real("near", 0.0, 100.0)) o.near_m = *v;
  if (auto v = args.real("far", 0.0, 100.0)) o.far_m = *v;
  if (auto v = args.integer("seed", 0, INT64_MAX)) o.seed = static_cast<std::uint64_t>(*v);
  return o;
}

}  // namespace

int crowd_command(std::span<char* const> words) {
  const ParsedArgs args = parse_args("crowd", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  const std::filesystem::path log = args.required("log");
  const std::filesystem::path out = args.required("out");
  const sim::CrowdOptions options = crowd_options(args);
  logs::ReaderOptions reader;
  reader.lenient = args.has("lenient");
  auto source = logs::open_scan_log(log, reader);
  const sim::CrowdedLog c = sim::make_crowd_file(*source, out, options);
  std::cout << std::fixed << std::setprecision(3) << "crowd around the robot from " << c.start
            << " to " << c.end << " s: " << c.crowded_scans << " scans, " << std::setprecision(1)
            << 100.0 * c.blocked_fraction << "% of their beams blocked\n"
            << "  log " << (out / "crowd.clf").string() << '\n';
  return 0;
}

}  // namespace mote::tool
