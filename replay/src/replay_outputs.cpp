// write_replay_outputs: the files of `mote replay --out DIR` (docs/outputs.md).
#include <fstream>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/logs/tum.hpp"
#include "mote/replay/map_image.hpp"
#include "mote/replay/profile.hpp"
#include "mote/replay/report.hpp"
#include "mote/replay/report_json.hpp"

namespace mote::replay {

void make_output_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw Error(dir.string() + ": the output folder is a file; name a folder (created if missing)");
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot create output folder: " + ec.message());
}

void write_replay_outputs(const std::filesystem::path& dir, const ReplayResult& result,
                          const ReportOptions& options) {
  make_output_folder(dir);
  std::ofstream json(dir / "report.json");
  write_report_json(json, result, options);
  if (!json.good()) throw Error((dir / "report.json").string() + ": cannot write");
  if (options.profile) {
    std::ofstream folded(dir / "profile.folded");
    write_folded_stacks(folded, profile_run(result));
    if (!folded.good()) throw Error((dir / "profile.folded").string() + ": cannot write");
  }
  logs::write_tum(dir / "trajectory.tum", result.trajectory);
  write_updates_csv(dir / "updates.csv", result);
  std::vector<LocalizationState> states;
  states.reserve(result.updates.size());
  for (const UpdateRecord& u : result.updates) states.push_back(u.state);
  const MapOverlay overlay{result.reference, result.trajectory, result.final_particles, states};
  write_map_png(dir / "map.png", result.map(), overlay);
}

}  // namespace mote::replay
