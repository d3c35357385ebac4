#pragma once
/// \file
/// mote::Localizer: the complete MCL update (design.md section 2) behind one class. Construct it
/// with a map and a LocalizerConfig, initialize it, then call update() with every odometry pose
/// and scan; read estimate() and last_update() after each.
///
/// Bad input never reaches the particles (tests/engine/test_bad_input.cpp):
///  - odometry with a NaN or infinite field: kRejectedOdometry, nothing changes;
///  - an odometry step longer than odom_jump_max_d (a driver restart, kilometres of drift):
///    kRejectedOdometry, taken as an odometry reset: the particles stay, later steps count from
///    the new odometry pose;
///  - a scan with non-finite beam angles (also after conversion to float), a NaN range limit, a
///    non-finite sensor pose, a range_max that is not positive and finite when the beam model
///    would ray-cast to it (laser_max_range < 0 takes the scan's), or
///    without a valid reading (all NaN, negative, below range_min; or all at max range with the
///    likelihood field, which ignores max-range readings as amcl does): kRejectedScan, nothing
///    changes. The beam model weighs all-max-range scans (eq. 6.12 at z = z_max);
///  - a scan no particle explains (every likelihood zero): kUnexplainedScan, weights left
///    uniform instead of NaN;
///  - a config with min_particles < 1 or other invalid values: ConfigError from the
///    constructor; a map without a free cell: ConfigError from initialize_global().
///
/// Threads: one Localizer must not be used from several threads at once (not even const
/// members during an update()); different Localizers may run concurrently, each on its own
/// task arena.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"
#include "mote/engine/beam_model.hpp"
#include "mote/engine/estimate.hpp"
#include "mote/engine/localization_state.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/engine/odometry_noise.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/scan_match.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

class RangeTable;

/// What the filter believes: the whole set and its clusters (connected occupied KLD bins).
struct LocalizationEstimate {
  PoseEstimate overall;                ///< the whole particle set
  std::vector<PoseEstimate> clusters;  ///< heaviest first
  /// The reported pose: the heaviest cluster's mean matched to the map with every valid reading
  /// of the last scan (scan_match.hpp), where the cluster supports the match (a chi-square gate
  /// on their covariances, docs/localization-state.md); else the mean itself with a zero
  /// covariance. Its pose is the mean when the scan had no endpoint. While the heaviest cluster
  /// lies at another place than the one the filter was tracking and has not yet out-explained
  /// it over a run of scans, the tracked place instead, carried by the odometry and matched to
  /// the scan (UpdateStats::held, hypothesis_hold.hpp).
  ScanMatch refined;
  /// The heaviest cluster (amcl reports this one as the robot's pose).
  [[nodiscard]] const PoseEstimate& best() const noexcept {
    return clusters.empty() ? overall : clusters.front();
  }
};

/// Why update() did or did not run the filter.
enum class UpdateOutcome : std::uint8_t {
  kUpdated,           ///< motion, sensor and (maybe) resampling ran
  kInitialized,       ///< first scan after initialize(): weighed without motion
  kNotMoved,          ///< below update_min_d / update_min_a: nothing changed
  kRejectedOdometry,  ///< odometry not finite, or a jump past odom_jump_max_d (reset)
  kRejectedScan,      ///< no valid beam, or non-finite scan geometry: nothing changed
  kUnexplainedScan,   ///< no particle explained the scan: weights left uniform (see reason)
};

/// Wall-clock milliseconds of each phase of the last update.
struct PhaseTimes {
  double motion = 0.0;
  double sensor = 0.0;
  double normalize = 0.0;  ///< with the tempering search and the scan fit
  double resample = 0.0;
  double estimate = 0.0;
  double total = 0.0;
};

/// Statistics of the last call to update().
struct UpdateStats {
  UpdateOutcome outcome = UpdateOutcome::kNotMoved;
  std::string reason;         ///< one line, for the outcomes that did not update normally
  std::uint64_t step = 0;     ///< filter updates run so far
  std::size_t particles = 0;  ///< particles after the update
  std::size_t weighed = 0;    ///< particles the scan weighed (before resampling)
  std::size_t beams = 0;      ///< beams weighed
  /// Beams selected but left out as blocked by something the map does not hold
  /// (unmapped_obstacle_filter); not in `beams`.
  std::size_t blocked_beams = 0;
  double effective_sample_size = 0.0;  ///< of the weighed set
  bool resampled = false;
  std::size_t injected = 0;  ///< augmented MCL's particles drawn from free space (amcl's rule)
  /// Particles a re-localization added over free space before this update's motion step
  /// (relocalize_when_lost); 0 on every other update.
  std::size_t relocalized = 0;
  /// Those particles were a local search (within one scan range of the reported pose, every
  /// heading), not a global set: the first re-localization since the filter last tracked is.
  bool relocalized_locally = false;
  double tempering = 1.0;    ///< likelihood exponent tau applied to this scan
  int tempering_trials = 0;  ///< ESS evaluations of the adaptive search (0 when fixed)
  /// log sum_i w_prev,i p(z | x_i)^tau over the weighed set: the filter's estimate of the
  /// scan's predictive likelihood p(z_t | z_1:t-1, u_1:t) under the tempered model
  /// (NormalizeResult::log_mean_likelihood), in nats. Summed over a run it is the log
  /// marginal likelihood of the log that parameter choices compare by. -inf when no particle
  /// explained the scan, 0 for an update that weighed no beam.
  double log_evidence = 0.0;
  /// The odometry noise the next motion step samples with (config's until adapted).
  OdometryAlphas alphas;
  /// Whether the filter knows where the robot is (localization_state.hpp).
  LocalizationState state = LocalizationState::kUncertain;
  /// Share of the scan's readings that end within sigma_hit of an obstacle's surface, and of
  /// the weighed beams that see through a mapped obstacle, from the refined best pose.
  double hit_share = 0.0;
  double see_through = 0.0;
  /// see_through + (1 - hit_share) averaged over the last updates: what the state is decided
  /// from (localization_state.hpp).
  double misfit = 0.0;
  /// The misfit above which the state is lost: lost_misfit, or higher where the map and laser
  /// fit worse while surely tracking (LocalizationMonitor::lost_bound).
  double lost_bound = 0.6;
  /// Whether the refined estimate is the match: it converged and the belief supported it
  /// (LocalizationEstimate::refined); false when the gate or convergence refused it, or the
  /// scan had no endpoint.
  bool refined_matched = false;
  /// The match converged but lay outside the chi-square gate of the belief (0.999: nominally
  /// one update in a thousand while the belief and the match describe the same pose).
  bool refined_gated = false;
  /// Places the belief holds a hypothesis at, at the scale of the scan (hypotheses whose
  /// endpoints would barely overlap count apart); `tracking` needs exactly one.
  std::size_t places = 0;
  /// The reported pose (LocalizationEstimate::refined) stayed on the place the filter was
  /// tracking, matched to this scan there, while a hypothesis at another place was heavier
  /// (hypothesis_hold.hpp); the state is then `uncertain` at best.
  bool held = false;
  /// The heavier hypothesis took the reported pose over at this update: it explained the scans
  /// better than the held place over a run of scans.
  bool switched = false;
  double log_w_slow = 0.0;  ///< augmented MCL's averages of the mean likelihood, log domain
  double log_w_fast = 0.0;
  PhaseTimes ms;
  [[nodiscard]] bool ran() const noexcept {
    return outcome == UpdateOutcome::kUpdated || outcome == UpdateOutcome::kInitialized ||
           outcome == UpdateOutcome::kUnexplainedScan;
  }
};

/// The global set initialize_global() and a re-localization draw over free space.
struct GlobalSetSize {
  std::size_t particles = 0;  ///< particles drawn
  double per_bin = 0.0;       ///< particles per KLD bin of free space they come to
  /// global_particles_per_bin would need more than max_particles on this map: the set is
  /// thinner than asked for (per_bin says how thin), and a look-alike place is likelier to win.
  bool capped = false;
};

/// Monte Carlo localization on a fixed occupancy grid.
class Localizer {
 public:
  /// Validates the config (ConfigError) and builds the sensor model's tables (distance field or
  /// Embree scene). The map is copied.
  Localizer(const OccupancyGrid& map, LocalizerConfig config);
  /// The same, sharing the caller's map instead of copying it (on a big map the copy costs a
  /// byte per cell and 4 bytes per free cell). Throws ConfigError on a null map.
  Localizer(std::shared_ptr<const OccupancyGrid> map, LocalizerConfig config);
  ~Localizer();
  Localizer(Localizer&&) noexcept;
  Localizer& operator=(Localizer&&) noexcept;
  Localizer(const Localizer&) = delete;
  Localizer& operator=(const Localizer&) = delete;

  /// max_particles particles drawn from N(mean, covariance) (full 3x3, m and rad).
  void initialize(const Pose2& mean, const Eigen::Matrix3d& covariance);
  /// max_particles particles uniform over the map's free space (global localization).
  /// Throws ConfigError when the map has no free cell.
  void initialize_global();

  /// One filter step from the odometry pose and the scan taken there. Returns true when the
  /// filter ran (see last_update().outcome). Throws mote::Error when called before initialize.
  /// Every input it can refuse is refused before anything changes (outcome and reason say
  /// why). Should it throw anyway (out of memory) after the motion step, that motion counts as
  /// applied (it is not applied again by the next call); the weights may then hold part of the
  /// scan, so re-initialize if that matters.
  bool update(const Pose2& odometry, const LaserScan& scan);

  /// Makes the next update() run the filter even when the robot has moved less than
  /// update_min_d and update_min_a (nav2's request_nomotion_update, amcl's force_update).
  void force_next_update() noexcept;

  /// The current estimate (computed at the end of each update and after initialization). The
  /// reference stays valid for the Localizer's lifetime, but its contents change with the next
  /// update() or initialize*(): copy what must outlive them.
  [[nodiscard]] const LocalizationEstimate& estimate() const noexcept;
  /// The particles and their normalized log-weights. The view points into the filter's
  /// buffers and ends at the next update() or initialize*(), which may resample into the
  /// other buffer or reallocate: do not keep it across those calls.
  [[nodiscard]] ConstParticleView particles() const noexcept;
  /// Statistics of the last update() call (contents change with the next update()).
  [[nodiscard]] const UpdateStats& last_update() const noexcept;
  [[nodiscard]] const LocalizerConfig& config() const noexcept;
  /// The size of the global set this map and config give, and whether max_particles cut it.
  [[nodiscard]] GlobalSetSize global_set() const noexcept;
  /// Threads the filter runs on.
  [[nodiscard]] int threads() const noexcept;
  /// The beam model's range table (ray_casting: table), or nullptr (its stats() say what it
  /// cost; mote/raycast/range_table.hpp).
  [[nodiscard]] const RangeTable* range_table() const noexcept;
  /// The beam model's choice between the range table and exact casting, and why; nullopt for
  /// the likelihood field.
  [[nodiscard]] std::optional<BeamCasting> beam_casting() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mote
