/// \file
/// Writing a simulation to disk, and finding the bundled floor plan.

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "mote/core/error.hpp"
#include "mote/logs/carmen_writer.hpp"
#include "mote/logs/tum.hpp"
#include "mote/sim/simulate.hpp"

namespace mote::sim {

namespace {

// sim.noise.yaml: the chosen noise under the config's names, so a calibration can be checked.
void write_noise(const std::filesystem::path& path, const SimulationConfig& c) {
  std::ofstream out(path);
  out.precision(9);
  out << "# The noise mote simulate drew this log with (sim.clf).\n";
  if (c.odometry_alphas) {
    const OdometryAlphaNoise& a = *c.odometry_alphas;
    out << "# odometry: Thrun et al. table 5.6 with scale biases\nalpha1: " << a.alpha1
        << "\nalpha2: " << a.alpha2 << "\nalpha3: " << a.alpha3 << "\nalpha4: " << a.alpha4
        << "\ntranslation_bias: " << a.translation_bias << "\nrotation_bias: " << a.rotation_bias
        << "\n";
  }
  if (c.range_mixture) {
    const RangeMixture& m = *c.range_mixture;
    out << "# ranges: the beam mixture of table 6.1\nz_hit: " << m.z_hit
        << "\nz_short: " << m.z_short << "\nz_max: " << m.z_max << "\nz_rand: " << m.z_rand
        << "\nsigma_hit: " << m.sigma_hit << "\nlambda_short: " << m.lambda_short << "\n";
  }
  if (!out) throw Error("cannot write '" + path.string() + "'");
}

}  // namespace

SimulationFiles write_simulation(const Simulation& sim, const std::filesystem::path& directory,
                                 const SimulationConfig& config) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error("cannot create directory '" + directory.string() + "': " + ec.message());
  SimulationFiles files{directory / "sim.clf", directory / "sim.gt.tum", {}};
  logs::write_carmen_log(files.log, sim.frames);
  logs::write_tum(files.ground_truth, sim.truth);
  if (config.odometry_alphas || config.range_mixture) {
    files.noise = directory / "sim.noise.yaml";
    write_noise(files.noise, config);
  }
  return files;
}

std::filesystem::path bundled_map_path() {
  // The source tree copy serves builds that are not installed; the install copy the rest.
  for (const char* candidate : {MOTE_BUNDLED_MAP_SOURCE, MOTE_BUNDLED_MAP_INSTALL}) {
    std::error_code ec;
    const std::filesystem::path path(candidate);
    if (std::filesystem::is_regular_file(path, ec)) return path;
  }
  throw Error(std::string("bundled floor plan not found at '") + MOTE_BUNDLED_MAP_SOURCE +
              "' or '" + MOTE_BUNDLED_MAP_INSTALL + "'");
}

}  // namespace mote::sim
