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
  /// At most half of the last kVerdictUpdates updates are lost and the last one is not: the
  /// scans fit the belief at the end of the run.
  bool localized = false;
  /// The last update is lost, but at most half of the last kVerdictUpdates are: the fit broke
  /// at the very end, too briefly to tell clutter the map lacks from a kidnapping. Neither
  /// localized nor lost; the exit status is 0, as for a localized run.
  bool unsure = false;
  std::size_t lost_last = 0;  ///< the lost updates that end the run, in a row
  /// s from the first scan, the last tracking update before them (an unsure run that tracked).
  std::optional<double> tracking_until_s;
  LocalizationState final_state = LocalizationState::kUncertain;
  /// s from the first scan: the start of the run's last unbroken stretch of tracking updates,
  /// when the run ends tracking (the filter's own "converged since", no reference needed).
  std::optional<double> tracking_since_s;
  std::size_t window = 0;       ///< updates the verdict read (the last kVerdictUpdates)
  std::size_t lost_at_end = 0;  ///< lost updates among them
  Pose2 final_pose;             ///< the last estimate (trajectory.tum's last row)
  double final_stamp = 0.0;     ///< s, its stamp
  std::string stamp_source;     ///< what the stamp is ("header.stamp", "ipc_timestamp")
  /// Empty when localized; else why the run is not to be trusted, in words for a user.
  /// An unsure run's warning is not a failure (exit_status).
  std::string warning;
};

/// The verdict on a finished run.
[[nodiscard]] RunVerdict judge_run(const ReplayResult& result);

/// The exit status of `mote replay` and `mote run` for the verdict: 0 when localized or unsure,
/// kExitEndsLost when it ends lost.
[[nodiscard]] int exit_status(const RunVerdict& v) noexcept;

/// The summary's rows (name, value): "localized" and "final pose".
[[nodiscard]] std::vector<std::pair<std::string, std::string>> verdict_rows(const RunVerdict& v);

/// The summary's "global set" row when a global set the run drew was capped at max_particles,
/// naming the draws (the global start, re-localizations); empty when the run drew none (a start
/// from a known pose that never re-localized) or none was capped.
[[nodiscard]] std::string capped_global_set_text(const ReplayResult& r);

/// report.json's "verdict": {localized, unsure, final_state, tracking_since_s, final_pose
/// {stamp, x, y, theta}, warning}.
void write_verdict_json(JsonWriter& json, const RunVerdict& v);

}  // namespace mote::replay
