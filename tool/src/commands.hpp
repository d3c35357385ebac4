#pragma once
// The mote tool's commands. Each returns the process exit status and throws UsageError (status 2)
// or mote::Error (status 1) on failure; main() turns those into one line on stderr. A replay that
// finishes but ends lost returns replay::kExitEndsLost (3).

#include <filesystem>
#include <span>

#include "mote/replay/replay_run.hpp"
#include "mote/replay/report.hpp"

namespace mote::tool {

/// `mote replay`: a recorded log through the filter; writes report.json, trajectory.tum, map.png.
int replay_command(std::span<char* const> args);
/// `mote simulate`: a simulated log on a map.
int simulate_command(std::span<char* const> args);
/// `mote kidnap`: a kidnapped-robot log spliced from a recorded log with reference poses.
int kidnap_command(std::span<char* const> args);
/// `mote crowd`: a recorded log with people standing around the robot for a stretch.
int crowd_command(std::span<char* const> args);
/// `mote info`: what a recorded log holds.
int info_command(std::span<char* const> args);
/// `mote calibrate`: sensor and motion model parameters fitted from a log.
int calibrate_command(std::span<char* const> args);
/// `mote node`: the live localizer on a ROS 2 graph over DDS.
int node_command(std::span<char* const> args);
/// `mote play`: a recorded log (and a map) published over DDS as ROS 2 topics.
int play_command(std::span<char* const> args);
/// `mote run`: simulate on the bundled floor plan, then replay with global initialization.
int run_command(std::span<char* const> args);

/// Runs a replay with a progress bar on stderr (when it is a terminal) and writes the outputs
/// into out_dir, with `viewer` also out_dir/viewer.html. Returns the replay's result.
replay::ReplayResult replay_and_report(replay::ReplayOptions options,
                                       const std::filesystem::path& out_dir,
                                       const replay::ReportOptions& report = {},
                                       bool viewer = false);

/// The verdict on a finished run: prints "mote COMMAND: warning: ..." on stderr when it is not
/// localized (ends lost, or unsure) and returns its replay::exit_status.
int warn_unless_localized(const char* command, const replay::ReplayResult& result);

}  // namespace mote::tool
