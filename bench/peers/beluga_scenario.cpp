#include "beluga_scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string_view>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/sim/simulate.hpp"

namespace mote::bench::peers {

namespace {

// bench_e2e's drive (e2e_world.cpp): 60 s, seed 7, a laser that sees every wall (no dropouts, a
// range beyond the map), so every beam of every scan is a valid return and both filters weigh
// all of them. One change: the laser sits on the base (no mounting offset), because Beluga's beam
// model casts its rays from the particle's pose, with bearings taken from the points in the base
// frame, where mote casts from the laser; with the laser on the base both models are exact.
sim::SimulationConfig drive_config(int beams) {
  sim::SimulationConfig config;
  config.seconds = 60.0;
  config.seed = 7;
  config.beams = beams;
  config.max_range = 81.83F;
  config.dropout_probability = 0.0;
  config.sensor_offset = Pose2{0.0, 0.0, 0.0};
  return config;
}

std::int8_t map_server_value(CellState state) {
  switch (state) {
    case CellState::kFree:
      return 0;
    case CellState::kOccupied:
      return 100;
    case CellState::kUnknown:
      break;
  }
  return -1;
}

PlainPose plain(const Pose2& p) { return {p.x, p.y, p.theta}; }

bool same(const Pose2& a, const Pose2& b) { return a.x == b.x && a.y == b.y && a.theta == b.theta; }

// FNV-1a, 64 bits, over the bytes of trivially copyable values.
struct Fnv {
  std::uint64_t h = 1469598103934665603ULL;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  void pose(const PlainPose& p) {
    value(p.x);
    value(p.y);
    value(p.theta);
  }
};

std::string checksum(const Scenario& s) {
  Fnv f;
  f.value(s.grid.width);
  f.value(s.grid.height);
  f.value(s.grid.resolution);
  f.pose(s.grid.origin);
  f.bytes(s.grid.cells.data(), s.grid.cells.size());
  f.value(s.scan.angle_min);
  f.value(s.scan.angle_increment);
  f.value(s.scan.range_min);
  f.value(s.scan.range_max);
  f.pose(s.scan.sensor);
  for (const Frame& frame : s.frames) {
    f.pose(frame.truth);
    f.pose(frame.odometry);
    f.bytes(frame.ranges.data(), frame.ranges.size() * sizeof(float));
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(f.h));
  return text;
}

[[noreturn]] void usage(const char* program, bool ray_casting, const std::string& problem) {
  std::fprintf(stderr,
               "%s: %s\nusage: %s --map MAP.yaml --model likelihood_field|beam --particles N "
               "--threads T --updates U [--beams B]%s\n",
               program, problem.c_str(), program,
               ray_casting ? " [--ray-casting exact|table]" : "");
  std::exit(2);
}

int positive(const char* program, bool ray_casting, std::string_view key, const char* value) {
  char* end = nullptr;
  const long v = std::strtol(value, &end, 10);
  if (end == value || *end != '\0' || v < 1 || v > 100'000'000) {
    usage(program, ray_casting, std::string(key) + " takes a positive integer");
  }
  return static_cast<int>(v);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double phase_median(const std::vector<UpdateTimes>& updates, double UpdateTimes::*phase) {
  std::vector<double> v;
  v.reserve(updates.size());
  for (const UpdateTimes& u : updates) v.push_back(u.*phase);
  return median(std::move(v));
}

std::string number(double v, int decimals) {
  if (!std::isfinite(v)) return "null";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

}  // namespace

std::size_t Scenario::frame(std::size_t k) const {
  const std::size_t period = 2 * (frames.size() - 1);
  const std::size_t phase = k % period;
  return phase < frames.size() ? phase : period - phase;
}

Scenario make_scenario(const std::string& map_yaml, int beams) {
  const OccupancyGrid map = load_map(map_yaml);
  const sim::SimulationConfig config = drive_config(beams);
  const sim::Simulation drive = sim::simulate(map, config);

  Scenario s;
  s.map_name = map_yaml;
  s.grid.width = map.width();
  s.grid.height = map.height();
  s.grid.resolution = map.resolution();
  s.grid.origin = plain(map.origin());
  s.grid.cells.reserve(map.cell_count());
  for (const CellState c : map.cells()) s.grid.cells.push_back(map_server_value(c));
  for (std::size_t i = 0; i < drive.frames.size(); ++i) {
    // A frame without odometry motion would not update mote's filter (kNotMoved): skip it.
    if (i > 0 && same(drive.frames[i - 1].odometry, drive.frames[i].odometry)) continue;
    const LaserScan& scan = drive.frames[i].scan;
    if (s.frames.empty()) {
      s.scan = {scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max,
                plain(scan.sensor_pose)};
    }
    s.frames.push_back({plain(drive.truth[i].pose), plain(drive.frames[i].odometry), scan.ranges});
  }
  if (s.frames.size() < 2) throw Error("the simulated drive has fewer than 2 frames");
  s.checksum = checksum(s);
  return s;
}

RunArgs parse_args(int argc, char** argv, const char* program, bool ray_casting) {
  RunArgs a;
  for (int i = 1; i < argc; i += 2) {
    const std::string_view key = argv[i];
    if (i + 1 >= argc) usage(program, ray_casting, std::string(key) + " needs a value");
    const char* value = argv[i + 1];
    if (key == "--map") {
      a.map = value;
    } else if (key == "--model") {
      a.model = value;
      if (a.model != "likelihood_field" && a.model != "beam") {
        usage(program, ray_casting, "--model is likelihood_field or beam");
      }
    } else if (key == "--ray-casting" && ray_casting) {
      a.ray_casting = value;
      if (a.ray_casting != "exact" && a.ray_casting != "table") {
        usage(program, ray_casting, "--ray-casting is exact or table");
      }
    } else if (key == "--particles") {
      a.particles = positive(program, ray_casting, key, value);
    } else if (key == "--threads") {
      a.threads = positive(program, ray_casting, key, value);
    } else if (key == "--updates") {
      a.updates = positive(program, ray_casting, key, value);
    } else if (key == "--beams") {
      a.beams = positive(program, ray_casting, key, value);
    } else {
      usage(program, ray_casting, "unknown argument " + std::string(key));
    }
  }
  if (a.map.empty() || a.model.empty() || a.particles == 0 || a.threads == 0 || a.updates == 0) {
    usage(program, ray_casting, "--map, --model, --particles, --threads and --updates are needed");
  }
  return a;
}

void print_result(const RunArgs& args, const Scenario& scenario, const RunResult& r) {
  const double total = phase_median(r.updates, &UpdateTimes::total);
  double sum = 0.0;
  for (const UpdateTimes& u : r.updates) sum += u.total;
  const double pb = static_cast<double>(r.particles) * static_cast<double>(r.beams);
  const double heading = std::remainder(r.estimate.theta - r.truth.theta, 2.0 * std::numbers::pi);
  std::printf(
      "{\"peer\": \"%s\", \"description\": \"%s\", \"model\": \"%s\", \"ray_casting\": \"%s\", "
      "\"threads\": %d, \"particles\": %zu, \"beams\": %zu, \"updates\": %zu, "
      "\"scenario\": \"%s\", \"frames\": %zu, "
      "\"update_ms\": {\"median\": %s, \"mean\": %s}, "
      "\"phase_ms\": {\"motion\": %s, \"sensor\": %s, \"normalize\": %s, \"resample\": %s, "
      "\"estimate\": %s}, \"particle_beams_per_s\": %s, \"final_error_m\": %s, "
      "\"final_heading_error_rad\": %s}\n",
      r.peer.c_str(), r.description.c_str(), args.model.c_str(), args.ray_casting.c_str(),
      args.threads, r.particles, r.beams, r.updates.size(), scenario.checksum.c_str(),
      scenario.frames.size(), number(total, 4).c_str(),
      number(sum / static_cast<double>(r.updates.size()), 4).c_str(),
      number(phase_median(r.updates, &UpdateTimes::motion), 4).c_str(),
      number(phase_median(r.updates, &UpdateTimes::sensor), 4).c_str(),
      number(phase_median(r.updates, &UpdateTimes::normalize), 4).c_str(),
      number(phase_median(r.updates, &UpdateTimes::resample), 4).c_str(),
      number(phase_median(r.updates, &UpdateTimes::estimate), 4).c_str(),
      number(total > 0.0 ? pb / (total * 1e-3) : std::nan(""), 0).c_str(),
      number(std::hypot(r.estimate.x - r.truth.x, r.estimate.y - r.truth.y), 4).c_str(),
      number(std::abs(heading), 4).c_str());
}

}  // namespace mote::bench::peers
