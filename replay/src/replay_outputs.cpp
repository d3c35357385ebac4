// write_replay_outputs: the files of `mote replay --out DIR` (docs/outputs.md).
#include <algorithm>
#include <fstream>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/logs/tum.hpp"
#include "mote/replay/map_image.hpp"
#include "mote/replay/profile.hpp"
#include "mote/replay/report.hpp"
#include "mote/replay/report_json.hpp"

namespace mote::replay {

std::size_t settled_index(const ReplayResult& result) {
  const std::vector<UpdateRecord>& u = result.updates;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const std::size_t end = std::min(u.size(), k + kSettledUpdates);
    const bool tracking = std::all_of(
        u.begin() + static_cast<std::ptrdiff_t>(k), u.begin() + static_cast<std::ptrdiff_t>(end),
        [](const UpdateRecord& r) { return r.state == LocalizationState::kTracking; });
    if (tracking) return k;
  }
  return u.size();
}

MapOverlay map_overlay(const ReplayResult& result, std::span<const LocalizationState> states) {
  MapOverlay o{result.reference, result.trajectory, result.final_particles, states};
  o.settled = std::min(settled_index(result), result.trajectory.size());
  if (!result.reference.empty()) {
    // Where the robot started: the reference pose of the first scan, as a tracking start uses.
    const std::vector<logs::StampedPose> sorted = logs::sort_by_stamp(result.reference);
    const auto match =
        logs::match_reference(sorted, result.first_stamp, logs::kReferenceMatchTolerance);
    o.start = match ? match->pose : sorted.front().pose;
    o.start_label = "start (reference)";
  } else if (result.global_start && o.settled > 0 && o.settled < result.trajectory.size()) {
    // A global start has no known start; its first estimates are guesses.
    o.start = result.trajectory[o.settled].pose;
    o.start_label = "first settled estimate";
  }
  return o;
}

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
  write_map_png(dir / "map.png", result.map(), map_overlay(result, states));
}

}  // namespace mote::replay
