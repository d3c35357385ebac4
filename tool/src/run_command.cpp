// `mote run` (what `make run` calls): simulate on the bundled floor plan, then replay the log
// with global initialization and print whether and how well the filter localized.
#include <array>
#include <filesystem>
#include <iostream>
#include <string>

#include "args.hpp"
#include "commands.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/replay/report.hpp"
#include "mote/sim/simulate.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 7> kFlags{{
    {"out", "DIR", "output folder (default ./mote-run)"},
    {"seconds", "S", "simulated time, s (default 60)"},
    {"seed", "N", "seed of the simulation and the filter (default 1)"},
    {"max-particles", "N", "KLD upper bound (default 500000, the library's)"},
    {"min-particles", "N", "KLD lower bound once converged (default 500)"},
    {"threads", "N", "worker threads, 0 = every core (default 0)"},
    {"viewer", "", "also DIR/viewer.html: the run in a browser (as mote replay --viewer)"},
}};

constexpr std::string_view kUsage = "mote run [--out DIR] [flags]";
constexpr std::string_view kAbout =
    "Simulates a robot on the bundled 20 m x 15 m office floor plan, replays the log with global\n"
    "initialization (the filter is not told where the robot starts) and prints the summary:\n"
    "converged or not, accuracy against the true poses, update time, particles. DIR holds\n"
    "sim.clf, sim.gt.tum, report.json, trajectory.tum, updates.csv and map.png (and viewer.html\n"
    "with --viewer).";

replay::ReplayOptions run_options(const ParsedArgs& args, const sim::SimulationFiles& files,
                                  std::uint64_t seed) {
  replay::ReplayOptions o;
  o.map = sim::bundled_map_path();
  o.log = files.log;
  o.reference = files.ground_truth;
  o.init = replay::InitMode::kGlobal;
  o.config.seed = seed;
  // Global localization spreads the first cloud over the whole floor plan (about 300 m^2 and
  // every heading), sized by global_particles_per_bin; KLD sampling (Fox 2003) shrinks it once
  // it converges. The library's defaults, as a user's first run gets them.
  o.config.max_particles = static_cast<int>(
      args.integer("max-particles", 1, 10'000'000).value_or(LocalizerConfig{}.max_particles));
  o.config.min_particles =
      static_cast<int>(args.integer("min-particles", 1, 10'000'000).value_or(500));
  o.config.threads = static_cast<int>(args.integer("threads", 0, 1024).value_or(0));
  return o;
}

// The bundled map's path as the user would type it: relative to the working directory when the
// map lies under it (`make run` in the checkout), else as it is.
std::string shown(const std::filesystem::path& path) {
  const std::filesystem::path relative = path.lexically_relative(std::filesystem::current_path());
  return !relative.empty() && *relative.begin() != ".." ? relative.string() : path.string();
}

}  // namespace

int run_command(std::span<char* const> words) {
  const ParsedArgs args = parse_args("run", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  const std::filesystem::path out = args.text("out").value_or("mote-run");
  sim::SimulationConfig sim_config;
  sim_config.seconds = args.real("seconds", 1.0, 3600.0).value_or(60.0);
  sim_config.seed = static_cast<std::uint64_t>(args.integer("seed", 0, INT64_MAX).value_or(1));
  std::cout << "mote run: simulating " << sim_config.seconds << " s on "
            << shown(sim::bundled_map_path()) << '\n';
  const sim::Simulation drive = sim::simulate(load_map(sim::bundled_map_path()), sim_config);
  const sim::SimulationFiles files = sim::write_simulation(drive, out);
  std::cout << "mote run: replaying " << drive.frames.size()
            << " scans with global initialization\n";
  const replay::ReplayResult result =
      replay_and_report(run_options(args, files, sim_config.seed), out, {}, args.has("viewer"));
  replay::print_summary(std::cout, result);
  std::cout << "  outputs               " << std::filesystem::absolute(out).string() << '\n';
  return warn_unless_localized("run", result);
}

}  // namespace mote::tool
