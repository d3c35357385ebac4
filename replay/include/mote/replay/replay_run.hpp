#pragma once
/// \file
/// The replay loop behind `mote replay`: feed a recorded log through a Localizer, collect the
/// estimated trajectory, per-update timings and outcome counts, and compare with a reference.

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/logs/tum.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/replay/metrics.hpp"
#include "mote/replay/range_table_report.hpp"

namespace mote::replay {

/// How the filter is initialized.
enum class InitMode : std::uint8_t {
  kAuto,    ///< at the reference pose of the first scan when a reference is given, else global
  kGlobal,  ///< uniform over free space (Thrun table 8.2, global localization)
  kPose,    ///< Gaussian around ReplayOptions::init_pose
};

/// Inputs of one replay run. The config is final (file and flags already merged).
struct ReplayOptions {
  std::filesystem::path map;        ///< map_server YAML
  std::filesystem::path log;        ///< CARMEN (.clf, .log) or ROS 1 bag (.bag)
  std::filesystem::path reference;  ///< TUM reference trajectory; empty = none
  LocalizerConfig config;
  logs::ReaderOptions reader;
  InitMode init = InitMode::kAuto;
  Pose2 init_pose;                   ///< m, rad; used by InitMode::kPose
  double init_sigma_xy = 0.1;        ///< m, std. dev. of the initial cloud in x and y
  double init_sigma_theta = 0.0873;  ///< rad (5 degrees), std. dev. of the initial heading
  MetricOptions metrics;             ///< start_stamp is set to the first scan's stamp
  /// s, stamp of a kidnapping (mote kidnap's splice): with a reference, the run measures how
  /// many updates the filter needs to recover (recovery_updates).
  std::optional<double> kidnapped_at;
  double recovered_within_m = 0.3;  ///< m, position error bound of a recovered estimate
  std::size_t recovered_hold = 20;  ///< consecutive matched updates within it that count
  /// Called after every scan with the number of scans processed so far; may be empty.
  std::function<void(std::size_t scans)> progress;
  /// Called after every update that ran (after its UpdateRecord) with the filter and the frame
  /// it ran on; may be empty. `mote replay --viewer` records the page's data here (viewer.hpp).
  std::function<void(const Localizer& filter, const logs::ScanFrame& frame)> on_update;
};

/// One filter update that ran.
struct UpdateRecord {
  double stamp = 0.0;  ///< s, the scan's stamp
  PhaseTimes ms;       ///< wall-clock phase times
  std::size_t particles = 0;
  std::size_t weighed = 0;
  std::size_t beams = 0;               ///< beams weighed
  std::size_t blocked_beams = 0;       ///< beams left out by unmapped_obstacle_filter
  double effective_sample_size = 0.0;  ///< of the weighed set
  double tempering = 1.0;              ///< likelihood exponent applied
  double log_evidence = 0.0;           ///< UpdateStats::log_evidence, nats
  std::size_t injected = 0;            ///< augmented MCL's particles (amcl's rule)
  std::size_t relocalized = 0;         ///< particles a re-localization added
  bool relocalized_locally = false;    ///< ... by a local search (UpdateStats)
  bool resampled = false;
  OdometryAlphas alphas;  ///< odometry noise in use after the update
  LocalizationState state = LocalizationState::kUncertain;  ///< UpdateStats::state
  double hit_share = 0.0;                                   ///< UpdateStats::hit_share
  double see_through = 0.0;                                 ///< UpdateStats::see_through
  double misfit = 0.0;                                      ///< UpdateStats::misfit
  double lost_bound = 0.6;                                  ///< UpdateStats::lost_bound
  std::size_t places = 0;                                   ///< UpdateStats::places
  bool held = false;      ///< UpdateStats::held: the reported pose stayed on the tracked place
  bool switched = false;  ///< UpdateStats::switched: another place took the reported pose over
  Pose2 refined;          ///< the reported pose (LocalizationEstimate::refined)
  Pose2 odometry;         ///< the scan's odometry pose (odom frame)
};

/// How a run recovered from a kidnapping (ReplayOptions::kidnapped_at).
struct KidnapRecovery {
  double at = 0.0;                ///< s, stamp of the kidnapping
  std::size_t updates_after = 0;  ///< updates that ran at or after it
  double within_m = 0.3;          ///< m, the bound used
  std::size_t hold = 20;          ///< consecutive updates within it required
  /// Updates spent lost before the recovered run (recovery_updates); nullopt = not recovered.
  std::optional<std::size_t> recovered_after;
};

/// Number of UpdateOutcome values (they are counted by their integer value).
inline constexpr std::size_t kOutcomeCount = 6;

/// Everything a replay run produced.
struct ReplayResult {
  /// An empty result for a run on `grid` with `cfg`.
  ReplayResult(OccupancyGrid map_grid, LocalizerConfig cfg)
      : grid(std::make_shared<const OccupancyGrid>(std::move(map_grid))), config(cfg) {}

  /// The map the run used.
  [[nodiscard]] const OccupancyGrid& map() const noexcept { return *grid; }

  std::shared_ptr<const OccupancyGrid> grid;  ///< the map, shared with the run's Localizer
  LocalizerConfig config;                     ///< the config it ran with
  int threads = 0;                            ///< threads the filter ran on
  GlobalSetSize global_set;                   ///< what a global start or a re-localization draws
  bool global_start = false;  ///< the filter started globally (drew global_set at the start)
  std::size_t scans = 0;      ///< scan frames read
  double first_stamp = 0.0;   ///< s, stamp of the first scan
  /// The estimate after every update that ran: the heaviest cluster's mean matched to the map
  /// (LocalizationEstimate::refined).
  std::vector<logs::StampedPose> trajectory;
  std::vector<logs::StampedPose> particle_trajectory;  ///< the heaviest cluster's mean itself
  std::vector<UpdateRecord> updates;                   ///< one per update that ran
  std::array<std::size_t, kOutcomeCount> outcomes{};   ///< update() calls by UpdateOutcome
  std::string first_unusual_reason;                    ///< reason of the first non-normal outcome
  logs::ReadStats reader;                              ///< what the log reader skipped
  float laser_range_max = 0.0F;  ///< m, range_max of the first scan (the laser's no-return value)
  std::string laser_range_max_source;  ///< where it came from (ScanSource::range_max_source)
  std::string stamp_source;            ///< what the stamps above are (ScanSource::stamp_source)
  std::vector<logs::StampedPose> reference;         ///< the reference trajectory (may be empty)
  std::optional<TrajectoryErrors> errors;           ///< with a reference
  std::optional<TrajectoryErrors> particle_errors;  ///< of particle_trajectory, with a reference
  std::optional<OffUpdates> off_updates;  ///< updates more than kOffUpdateM off, with a reference
  std::optional<KidnapRecovery> kidnap;   ///< with a reference and kidnapped_at
  std::vector<Pose2> final_particles;     ///< the particle cloud after the last scan
  double wall_s = 0.0;                    ///< s, wall-clock time of the whole loop
  double read_s = 0.0;                    ///< s of wall_s spent in the log reader's next()
  std::optional<RangeTableSummary> range_table;  ///< the beam model's table (ray_casting: table)
  std::optional<BeamCasting> beam_casting;       ///< the beam model's table or exact casting
};

/// Loads the map, log and reference, runs the filter over every scan and measures the result.
/// Throws InputError for malformed files, ConfigError for an invalid config.
[[nodiscard]] ReplayResult run_replay(const ReplayOptions& options);

/// Name of an outcome as written in reports ("updated", "not_moved", ...).
[[nodiscard]] const char* outcome_name(UpdateOutcome outcome) noexcept;

/// Name of a laser model as on the command line ("likelihood_field", "beam").
[[nodiscard]] const char* model_name(LaserModel model) noexcept;

}  // namespace mote::replay
