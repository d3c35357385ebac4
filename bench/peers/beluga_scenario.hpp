#pragma once
/// \file
/// The scenario bench/compare-beluga runs both filters through, and what each of its drivers
/// (beluga_driver.cpp, Beluga's particle filter; beluga_mote.cpp, mote's Localizer) reads and
/// prints. The Intel map, a drive simulated by mote's own simulator (mote::sim) through its free
/// space, and the scan taken at every step of it; both drivers build the same scenario from the
/// same map and seed, and print its checksum so the script can check that they did.
///
/// Plain C++17 types only: the Beluga driver includes this header and is compiled as Beluga
/// builds itself (C++17); beluga_scenario.cpp, compiled with mote, fills them.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mote::bench::peers {

/// A pose in the map frame (m, rad).
struct PlainPose {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

/// The occupancy grid as map_server publishes it: row-major from the bottom row, the lower-left
/// corner of cell (0, 0) at `origin`; 0 free, 100 occupied, -1 unknown.
struct PlainGrid {
  int width = 0;
  int height = 0;
  double resolution = 0.0;  ///< m per cell
  PlainPose origin;
  std::vector<std::int8_t> cells;
};

/// What every scan of the drive shares (sensor_msgs/LaserScan's fields).
struct ScanGeometry {
  float angle_min = 0.0F;        ///< rad, first beam in the sensor frame
  float angle_increment = 0.0F;  ///< rad between beams
  float range_min = 0.0F;        ///< m
  float range_max = 0.0F;        ///< m
  PlainPose sensor;              ///< the laser's mounting pose in the base frame
};

/// One step of the drive.
struct Frame {
  PlainPose truth;            ///< true base pose
  PlainPose odometry;         ///< drifting odometry
  std::vector<float> ranges;  ///< the scan, one range per beam
};

/// The map, the drive and its scans.
struct Scenario {
  std::string map_name;
  PlainGrid grid;
  ScanGeometry scan;
  std::vector<Frame> frames;  ///< every frame's odometry differs from the previous one's
  std::string checksum;       ///< FNV-1a over the grid, the geometry and the frames, in hex

  /// The frame of update k (k = 0: the initialization): the drive forward, then back over the
  /// same poses, so the robot never jumps however many updates a run asks for.
  [[nodiscard]] std::size_t frame(std::size_t k) const;
};

/// Simulates the scenario on the map of `map_yaml` (map_server YAML) with `beams` beams per scan.
/// Throws on a map that cannot be read or a drive of fewer than 2 frames.
[[nodiscard]] Scenario make_scenario(const std::string& map_yaml, int beams);

/// Both drivers' command line:
///   --map MAP.yaml --model likelihood_field|beam --particles N --threads T --updates U
///   [--beams B] [--ray-casting exact|table (mote only)]
struct RunArgs {
  std::string map;
  std::string model;                  ///< "likelihood_field" or "beam"
  std::string ray_casting = "exact";  ///< the beam model's expected ranges (mote only)
  int particles = 0;
  int threads = 0;
  int updates = 0;  ///< timed updates, after the untimed first weighing at the start pose
  int beams = 60;
};

/// Parses the flags above; prints the usage and exits with status 2 on anything else.
/// `ray_casting` says whether the program takes --ray-casting.
[[nodiscard]] RunArgs parse_args(int argc, char** argv, const char* program, bool ray_casting);

/// Wall-clock milliseconds of one update, split by phase where the filter says.
struct UpdateTimes {
  double motion = 0.0;
  double sensor = 0.0;
  double normalize = 0.0;
  double resample = 0.0;
  double estimate = 0.0;
  double total = 0.0;  ///< the whole update, as the driver's clock saw it
};

/// What a driver prints: one JSON object on stdout.
struct RunResult {
  std::string peer;         ///< "beluga" or "mote"
  std::string description;  ///< the filter's configuration in words
  std::vector<UpdateTimes> updates;
  std::size_t particles = 0;  ///< particles each update weighed
  std::size_t beams = 0;      ///< beams each update weighed
  PlainPose estimate;         ///< after the last update
  PlainPose truth;            ///< at the last update
};

/// Prints `result` as one line of JSON: the medians of each phase over the updates, the
/// particle-beams per second at the median update time, and the final position and heading
/// errors.
void print_result(const RunArgs& args, const Scenario& scenario, const RunResult& result);

/// The initial belief of both filters: a Gaussian around the true pose of frame 0 with these
/// variances (m^2, m^2, rad^2), as bench_e2e starts its tracking cases.
inline constexpr double kStartVariance[3] = {0.01, 0.01, 0.003};

}  // namespace mote::bench::peers
