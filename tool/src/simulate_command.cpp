// `mote simulate`: a simulated CARMEN log and its true trajectory for a map.
#include <array>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "args.hpp"
#include "commands.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/sim/simulate.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 14> kFlags{{
    {"map", "MAP.yaml", "map_server map to drive in (required)"},
    {"out", "DIR", "output folder for sim.clf and sim.gt.tum, created if missing (required)"},
    {"seconds", "S", "simulated time, s (default 60)"},
    {"seed", "N", "random seed for start pose, goals and noise (default 1)"},
    {"beams", "N", "laser beams per scan over 180 degrees (default 181)"},
    {"speed", "M/S", "cruise speed, m/s (default 0.5)"},
    {"range-noise", "M", "std. dev. of the range error, m (default 0.02)"},
    {"odom-noise", "SCALE", "factor on the odometry drift model (default 1; 0 = exact)"},
    {"max-range", "M", "laser maximum range, m (default 20)"},
    {"scan-rate", "HZ", "scans (and odometry samples) per second (default 10)"},
    {"alphas", "A1,A2,A3,A4",
     "odometry noise from the motion model itself (table 5.6, amcl's alpha1..alpha4) instead of "
     "the drift model; written to DIR/sim.noise.yaml"},
    {"odom-bias", "T,R", "with --alphas: scale errors of translation and rotation (default 0,0)"},
    {"mixture", "HIT,SHORT,MAX,RAND",
     "ranges from the beam mixture (table 6.1) with these weights (sum 1) instead of "
     "--range-noise; written to DIR/sim.noise.yaml"},
    {"mixture-shape", "SIGMA,LAMBDA",
     "with --mixture: sigma_hit (m) and lambda_short (1/m) (default 0.05,0.5)"},
}};

constexpr std::string_view kUsage = "mote simulate --map MAP.yaml --out DIR [flags]";
constexpr std::string_view kAbout =
    "Drives a simulated differential-drive robot between random goals in the map's free space\n"
    "and writes DIR/sim.clf (CARMEN: drifting odometry + ROBOTLASER1 scans at 10 Hz) and\n"
    "DIR/sim.gt.tum (true poses at the scan stamps), ready for mote replay --reference.";

void scale_noise(sim::OdometryNoise& n, double f) {
  n.translation *= f;
  n.rotation *= f;
  n.rotation_per_metre *= f;
  n.translation_bias *= f;
  n.rotation_bias *= f;
}

// A comma-separated list of exactly n numbers.
std::vector<double> numbers(const ParsedArgs& args, std::string_view flag, std::size_t n) {
  const std::string text = *args.text(flag);
  std::vector<double> v;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const auto x = parse_real(std::string_view(text).substr(start, comma - start));
    if (!x) break;
    v.push_back(*x);
    start = comma + 1;
  }
  if (v.size() != n) {
    throw args.error(
        flag, "expects " + std::to_string(n) + " comma-separated numbers, got '" + text + "'");
  }
  return v;
}

void noise_knobs(const ParsedArgs& args, sim::SimulationConfig& c) {
  if (args.has("alphas")) {
    const std::vector<double> a = numbers(args, "alphas", 4);
    sim::OdometryAlphaNoise n{a[0], a[1], a[2], a[3], 0.0, 0.0};
    if (args.has("odom-bias")) {
      const std::vector<double> b = numbers(args, "odom-bias", 2);
      n.translation_bias = b[0];
      n.rotation_bias = b[1];
    }
    c.odometry_alphas = n;
  } else if (args.has("odom-bias")) {
    throw args.error("odom-bias", "needs --alphas");
  }
  if (args.has("mixture")) {
    const std::vector<double> w = numbers(args, "mixture", 4);
    sim::RangeMixture m{w[0], w[1], w[2], w[3], 0.05, 0.5};
    if (args.has("mixture-shape")) {
      const std::vector<double> s = numbers(args, "mixture-shape", 2);
      m.sigma_hit = s[0];
      m.lambda_short = s[1];
    }
    c.range_mixture = m;
  } else if (args.has("mixture-shape")) {
    throw args.error("mixture-shape", "needs --mixture");
  }
}

sim::SimulationConfig simulation_config(const ParsedArgs& args) {
  sim::SimulationConfig c;
  if (auto s = args.real("seconds", 0.1, 1e6)) c.seconds = *s;
  if (auto n = args.integer("seed", 0, INT64_MAX)) c.seed = static_cast<std::uint64_t>(*n);
  if (auto n = args.integer("beams", 2, 100'000)) c.beams = static_cast<int>(*n);
  if (auto v = args.real("speed", 0.01, 10.0)) c.speed = *v;
  if (auto v = args.real("range-noise", 0.0, 10.0)) c.range_noise = *v;
  if (auto v = args.real("odom-noise", 0.0, 100.0)) scale_noise(c.odometry, *v);
  if (auto v = args.real("max-range", 0.1, 1000.0)) c.max_range = static_cast<float>(*v);
  if (auto v = args.real("scan-rate", 0.1, 1000.0)) c.scan_rate = *v;
  noise_knobs(args, c);
  return c;
}

}  // namespace

int simulate_command(std::span<char* const> words) {
  const ParsedArgs args = parse_args("simulate", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  const std::filesystem::path map_path = args.required("map");
  const std::filesystem::path out = args.required("out");
  const sim::SimulationConfig config = simulation_config(args);
  const sim::Simulation drive = sim::simulate(load_map(map_path), config);
  const sim::SimulationFiles files = sim::write_simulation(drive, out, config);
  std::cout << "simulated " << drive.frames.size() << " scans (" << config.seconds << " s, "
            << drive.goals_reached << " goals reached)\n  log          " << files.log.string()
            << "\n  ground truth " << files.ground_truth.string() << '\n';
  if (!files.noise.empty()) std::cout << "  noise        " << files.noise.string() << '\n';
  return 0;
}

}  // namespace mote::tool
