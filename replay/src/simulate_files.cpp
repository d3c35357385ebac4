/// \file
/// Writing a simulation to disk, and finding the bundled floor plan.

#include <filesystem>
#include <string>
#include <system_error>

#include "mote/core/error.hpp"
#include "mote/replay/carmen_writer.hpp"
#include "mote/replay/simulate.hpp"
#include "mote/replay/tum.hpp"

namespace mote::replay {

SimulationFiles write_simulation(const Simulation& sim, const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error("cannot create directory '" + directory.string() + "': " + ec.message());
  SimulationFiles files{directory / "sim.clf", directory / "sim.gt.tum"};
  write_carmen_log(files.log, sim.frames);
  write_tum(files.ground_truth, sim.truth);
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

}  // namespace mote::replay
