#pragma once
/// \file
/// A crowd test made from a recorded log: for a stretch of the log, people stand in a ring
/// close around the robot and block most of its beams, as on a real log where a group gathers
/// around a robot turning on the spot. The people stand still in the odometry frame, so they
/// turn through the scans as the robot turns; every other reading, and the odometry, stays as
/// recorded. A filter must ride this out on odometry and the few beams that still see the walls.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <vector>

#include "mote/logs/scan_source.hpp"

namespace mote::sim {

/// Where the crowd stands and for how long.
struct CrowdOptions {
  double seconds = 20.0;  ///< s, how long the crowd stays
  /// s, stamp of the first crowded scan; NaN: the start of the `seconds` window in which the
  /// odometry turns the most while it travels less than `max_travel_m` (turning on the spot).
  double start = std::numeric_limits<double>::quiet_NaN();
  double max_travel_m = 1.0;   ///< m, the most the robot may travel in an automatic window
  int people = 8;              ///< people in the ring, evenly spaced in bearing (with jitter)
  double near_m = 0.4;         ///< m, the ring's inner distance from the robot
  double far_m = 1.0;          ///< m, its outer distance
  double person_radius = 0.2;  ///< m, a person's cross-section as seen by the laser
  std::uint64_t seed = 1;      ///< draws the people's bearings and distances
};

/// A log with a crowd in it.
struct CrowdedLog {
  std::vector<logs::ScanFrame> frames;  ///< the log, scans in the window with the crowd's readings
  double start = 0.0;                   ///< s, stamp of the first crowded scan
  double end = 0.0;                     ///< s, stamp of the last crowded scan
  std::size_t crowded_scans = 0;        ///< scans in the window
  double blocked_fraction = 0.0;        ///< beams the crowd shortened / beams, over the window
};

/// Puts a crowd into `frames` (in log order). Throws ConfigError on options out of range
/// (seconds <= 0, people < 1, 0 < near_m <= far_m, person_radius > 0) or when the log is
/// shorter than the window.
[[nodiscard]] CrowdedLog make_crowded_log(std::vector<logs::ScanFrame> frames,
                                          const CrowdOptions& options = {});

/// Reads every frame of `source`, adds the crowd and writes out_dir/crowd.clf (CARMEN, see
/// carmen_writer.hpp), creating out_dir if needed. Throws mote::Error when the file cannot be
/// written, InputError on malformed input.
CrowdedLog make_crowd_file(logs::ScanSource& source, const std::filesystem::path& out_dir,
                           const CrowdOptions& options = {});

}  // namespace mote::sim
