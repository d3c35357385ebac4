#include "e2e_world.hpp"

#include <filesystem>
#include <utility>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/sim/simulate.hpp"
#include "mote_bench/data.hpp"

namespace mote::bench {

namespace {

// A SICK LMS-like laser that sees every wall: no dropouts and a range beyond the map, so every
// beam of a scan is a valid return and a case's beam count is the count the models use.
sim::SimulationConfig drive_config(int beams) {
  sim::SimulationConfig config;
  config.seconds = 60.0;
  config.seed = 7;
  config.beams = beams;
  config.max_range = 81.83F;
  config.dropout_probability = 0.0;
  return config;
}

World empty_world(std::string name, OccupancyGrid map) {
  return World{
      .map_name = std::move(name), .map = std::move(map), .truth = {}, .odometry = {}, .scans = {}};
}

// Intel when ../shared/data has it, else the map bundled with mote.
World map_world() {
  const std::filesystem::path intel = data_dir() / "intel/intel.yaml";
  if (std::filesystem::exists(intel)) return empty_world("intel", load_map(intel));
  return empty_world("floorplan (bundled; Intel not found in " + data_dir().string() + ")",
                     load_map(sim::bundled_map_path()));
}

bool same(const Pose2& a, const Pose2& b) { return a.x == b.x && a.y == b.y && a.theta == b.theta; }

// Adds the frames of one simulation. The simulator keys every random draw by scan index and
// purpose, so runs that differ only in beam count drive the same poses; checked here because
// the benchmark pairs each beam count's scans with one trajectory.
void add_scans(World& w, int beams) {
  const sim::Simulation drive = sim::simulate(w.map, drive_config(beams));
  const bool first = w.truth.empty();
  std::vector<LaserScan>& scans = w.scans[beams];
  std::size_t kept = 0;
  for (std::size_t i = 0; i < drive.frames.size(); ++i) {
    // A frame without odometry motion would not update the filter (kNotMoved): skip it.
    if (i > 0 && same(drive.frames[i - 1].odometry, drive.frames[i].odometry)) continue;
    if (first) {
      w.truth.push_back(drive.truth[i].pose);
      w.odometry.push_back(drive.frames[i].odometry);
    } else if (kept >= w.truth.size() || !same(w.truth[kept], drive.truth[i].pose)) {
      throw Error("bench_e2e: the simulated drive differs between beam counts");
    }
    scans.push_back(drive.frames[i].scan);
    ++kept;
  }
}

World build_world() {
  World w = map_world();
  for (const int beams : kBeamCounts) add_scans(w, beams);
  if (w.truth.size() < 2) throw Error("bench_e2e: the simulated drive has fewer than 2 frames");
  return w;
}

}  // namespace

std::size_t World::frame(std::uint64_t k) const noexcept {
  const std::uint64_t period = 2 * (truth.size() - 1);
  const std::uint64_t phase = k % period;
  return static_cast<std::size_t>(phase < truth.size() ? phase : period - phase);
}

const LaserScan& World::scan(int beams, std::size_t frame) const {
  return scans.at(beams).at(frame);
}

const World& world() {
  static const World w = build_world();
  return w;
}

LaserScan middle_beam(const LaserScan& scan) {
  LaserScan one = scan;
  const std::size_t mid = scan.size() / 2;
  one.angle_min = static_cast<float>(scan.beam_angle(mid));
  one.ranges.assign(1, scan.ranges[mid]);
  return one;
}

}  // namespace mote::bench
