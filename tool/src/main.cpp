// mote: the command-line tool (replay, simulate, run). Exit status 0 on success, 2 for bad
// usage, 1 for bad input or a failed run; errors are one line on stderr.
#include <algorithm>
#include <array>
#include <iostream>
#include <span>
#include <string>
#include <string_view>

#include "args.hpp"
#include "commands.hpp"
#include "mote/core/did_you_mean.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/isa.hpp"

namespace {

constexpr std::string_view kHelp =
    "usage: mote COMMAND [flags]\n\n"
    "Monte Carlo localization on 2D occupancy grids.\n\n"
    "commands:\n"
    "  replay    run a recorded log (CARMEN .clf, ROS 1 .bag, ROS 2 rosbag2 folder, .mcap or\n"
    "            .db3) through the filter and write report.json, trajectory.tum and map.png\n"
    "  simulate  write a simulated log (CARMEN) and its reference trajectory for a map\n"
    "  kidnap    splice a kidnapped-robot test from a log with reference poses (for\n"
    "            mote replay --kidnapped-at)\n"
    "  crowd     put a ring of people around the robot for a stretch of a log (a test of\n"
    "            riding out readings the map cannot explain)\n"
    "  info      print what a log holds: format, duration, messages per topic, the laser's\n"
    "            beams, field of view and range limits, and the tf frames\n"
    "  calibrate fit the sensor and motion model parameters to a log (with or without\n"
    "            reference poses) and write config.yaml and calibration.png\n"
    "  node      localize live on a ROS 2 graph over DDS (no ROS needed): scans, /map and /tf\n"
    "            in; map -> odom, /amcl_pose, /particle_cloud and the state out\n"
    "  play      publish a recorded log (ROS 2 bag or CARMEN) and a map over DDS as ROS 2\n"
    "            topics, at the recorded rate or faster\n"
    "  run       simulate ~60 s on the bundled floor plan, replay it with global\n"
    "            initialization and print the summary (what `make run` calls)\n\n"
    "`mote COMMAND --help` lists each command's flags with units and defaults;\n"
    "`mote --version` prints the version and the kernel variant in use (MOTE_ISA).\n";

constexpr std::array<std::string_view, 9> kCommands{"replay", "simulate",  "kidnap", "crowd", "run",
                                                    "info",   "calibrate", "node",   "play"};

// "mote COMMAND: " for a command's errors, "mote: " before there is one.
std::string prefix(std::string_view command) {
  return std::ranges::find(kCommands, command) != kCommands.end()
             ? "mote " + std::string(command) + ": "
             : std::string("mote: ");
}

int dispatch(std::string_view command, std::span<char* const> rest) {
  if (command == "replay") return mote::tool::replay_command(rest);
  if (command == "simulate") return mote::tool::simulate_command(rest);
  if (command == "kidnap") return mote::tool::kidnap_command(rest);
  if (command == "crowd") return mote::tool::crowd_command(rest);
  if (command == "run") return mote::tool::run_command(rest);
  if (command == "info") return mote::tool::info_command(rest);
  if (command == "calibrate") return mote::tool::calibrate_command(rest);
  if (command == "node") return mote::tool::node_command(rest);
  if (command == "play") return mote::tool::play_command(rest);
  if (command == "--version" || command == "version") {
    std::cout << "mote " << MOTE_VERSION << "\nkernels: " << mote::isa_description() << '\n';
    return 0;
  }
  if (command == "--help" || command == "-h" || command == "help") {
    std::cout << kHelp;
    return 0;
  }
  const std::string best = mote::closest_word(command, kCommands);
  throw mote::tool::UsageError("mote: unknown command '" + std::string(command) + "'" +
                               (best.empty() ? "" : " (did you mean 'mote " + best + "'?)") +
                               " (see mote --help)");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << kHelp;
    return 2;
  }
  try {
    const std::span<char* const> rest(argv + 2, static_cast<std::size_t>(argc - 2));
    return dispatch(argv[1], rest);
  } catch (const mote::tool::UsageError& e) {
    std::cerr << e.what() << '\n';
    return 2;
  } catch (const mote::Error& e) {
    std::cerr << prefix(argv[1]) << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << prefix(argv[1]) << e.what() << '\n';
    return 1;
  }
}
