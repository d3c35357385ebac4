#pragma once
/// \file
/// Whether a run localized, from the filter's own localization state (localization_state.hpp),
/// so that a run without reference poses gets an answer: the summary's "localized" and "final
/// pose" rows, report.json's "verdict" object and the tool's exit status.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/replay/replay_run.hpp"
#include "mote/replay/report_json.hpp"

namespace mote::replay {

/// The exit status of `mote replay` and `mote run` for a run that finished but ends lost.
inline constexpr int kExitEndsLost = 3;

/// The updates at the end of a run the verdict reads: a run ends lost when more than half of
/// them are lost.
inline constexpr std::size_t kVerdictUpdates = 20;

/// What the run's localization states say about it.
struct RunVerdict {
  bool ran = false;  ///< at least one update ran (otherwise nothing below means anything)
  /// At most half of the last kVerdictUpdates updates are lost: the scans fit the belief at
  /// the end of the run.
  bool localized = false;
  LocalizationState final_state = LocalizationState::kUncertain;
  /// s from the first scan: the start of the final stretch of updates without a lost one, when
  /// the run ends tracking (the filter's own "converged since", no reference needed).
  std::optional<double> tracking_since_s;
  std::size_t window = 0;       ///< updates the verdict read (the last kVerdictUpdates)
  std::size_t lost_at_end = 0;  ///< lost updates among them
  Pose2 final_pose;             ///< the last estimate (trajectory.tum's last row)
  double final_stamp = 0.0;     ///< s, its stamp
  /// Empty when localized; else why the run is not to be trusted, in words for a user.
  std::string warning;
};

/// The verdict on a finished run.
[[nodiscard]] RunVerdict judge_run(const ReplayResult& result);

/// The summary's rows (name, value): "localized" and "final pose".
[[nodiscard]] std::vector<std::pair<std::string, std::string>> verdict_rows(const RunVerdict& v);

/// report.json's "verdict": {localized, final_state, tracking_since_s, final_pose {stamp, x, y,
/// theta}, warning}.
void write_verdict_json(JsonWriter& json, const RunVerdict& v);

}  // namespace mote::replay
