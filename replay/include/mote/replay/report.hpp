#pragma once
/// \file
/// What `mote replay` writes: report.json (figures of the run), trajectory.tum (the estimate)
/// and map.png (map, trajectories, final particles), plus the summary table it prints.

#include <filesystem>
#include <iosfwd>
#include <span>

#include "mote/replay/map_image.hpp"
#include "mote/replay/metrics.hpp"
#include "mote/replay/replay_run.hpp"

namespace mote::replay {

/// Figures derived from the per-update records of a run.
struct RunFigures {
  std::size_t updates = 0;      ///< filter updates that ran
  double particles_mean = 0.0;  ///< mean particle count after those updates
  Percentiles update_ms;        ///< total update time, ms
  PhaseTimes phase_mean_ms;     ///< mean time of each phase, ms
  /// Particles x beams weighed per second of update time (the sum of UpdateStats::ms.total),
  /// the definition of bench_e2e's particle_beams/s counter.
  double particle_beams_per_s = 0.0;
};

/// Figures of a run.
[[nodiscard]] RunFigures run_figures(const ReplayResult& result);

/// What goes into the outputs beyond the defaults.
struct ReportOptions {
  /// Adds "profile" (per-phase percentiles, histograms, ns per particle; see profile.hpp) to
  /// report.json, writes profile.folded (folded stacks, microseconds) and prints the phase table.
  bool profile = false;
};

/// Writes report.json's content: updates, scans, threads, isa, isa_detail, model, particles_mean,
/// update_ms {mean,p50,p99,max}, phase_ms, particle_beams_per_s, laser_max_range {m, source,
/// effective_m (after the config's laser_max_range)}, outcomes, reader stats, and with a
/// reference ate_rmse_m, heading_rmse_deg, converged_at_s (null when never or undefined) and
/// updates_over_1m, updates_over_1m_flagged, updates_over_1m_tracking (count_off_updates), and
/// after a kidnapping "kidnap" {at, updates_after, within_m, hold, recovered,
/// recovered_after_updates (null when not recovered)}.
void write_report_json(std::ostream& out, const ReplayResult& result,
                       const ReportOptions& options = {});

/// Prints the human-readable summary table.
void print_summary(std::ostream& out, const ReplayResult& result,
                   const ReportOptions& options = {});

/// Writes one CSV line per update that ran: stamp, particles, weighed, beams, blocked_beams, ess,
/// tempering,
/// scan_fit, log_evidence, injected, resampled, alpha1..alpha4, total_ms. Throws mote::Error when
/// it cannot be written.
void write_updates_csv(const std::filesystem::path& file, const ReplayResult& result);

/// Tracking updates in a row from which map.png joins the estimate into a line.
inline constexpr std::size_t kSettledUpdates = 5;

/// The first update from which the run tracked kSettledUpdates updates in a row (or to its end):
/// where the filter settled. updates.size() when it never did.
[[nodiscard]] std::size_t settled_index(const ReplayResult& result);

/// map.png's overlay for a run: the estimate joined from settled_index on, and the start marker
/// where the robot started (the reference pose of the first scan) or, for a global start
/// without a reference, at the first settled estimate, labelled so; `states` is one per update.
[[nodiscard]] MapOverlay map_overlay(const ReplayResult& result,
                                     std::span<const LocalizationState> states);

/// Creates the output folder `dir` if needed. Throws mote::Error naming it when it is a file or
/// cannot be made, so that a command can check it before a replay that takes minutes.
void make_output_folder(const std::filesystem::path& dir);

/// Creates `dir` if needed and writes report.json, trajectory.tum, updates.csv and map.png into it
/// (and profile.folded with options.profile). Throws mote::Error when a file cannot be written.
void write_replay_outputs(const std::filesystem::path& dir, const ReplayResult& result,
                          const ReportOptions& options = {});

}  // namespace mote::replay
