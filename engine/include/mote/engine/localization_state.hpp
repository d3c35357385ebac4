#pragma once
/// \file
/// Whether the filter knows where the robot is: tracking, uncertain or lost, decided after every
/// update from how the scan fits the belief's best hypothesis once matched to the map
/// (scan_match.hpp), against what the sensor model allows at the true pose.
///
/// Two shares of the scan, seen from the refined pose, make up the evidence:
/// - the see-through share: readings whose ray runs into a mapped obstacle, by more than twice
///   sigma_hit and at 30 degrees or more, before it ends (the weighed beams). At the true pose
///   the beam model (Thrun et al., table 6.1) explains such a reading only as a random one
///   (eq. 6.11) or the far tail of the hit Gaussian (eq. 6.4), and a map only by an error (glass,
///   a door drawn closed); at a wrong pose a reading crosses a wall wherever the belief puts one
///   between the robot and the endpoint, however well the endpoints happen to lie near walls;
/// - the hit share: readings that end within sigma_hit of an obstacle's surface (every valid
///   reading), which the likelihood field rewards (table 6.3).
/// The misfit is the see-through share plus the share of readings that are not hits: the part of
/// the scan the map contradicts plus the part it does not explain, in [0, 2]. It is smoothed over
/// a few updates, since single scans vary (a crowd, glass, a tight turn).
///
/// - lost: the smoothed misfit is above lost_misfit (the scans do not fit where the belief is);
/// - tracking: it is not, and the belief is focused: clusters tight enough that their spread
///   moves an endpoint by less than the hit band hold most of the weight (a fresh global set is
///   one connected cluster holding all of it, but metres wide);
/// - uncertain: otherwise: the scans fit, but the belief has several hypotheses or is spread
///   out (global localization before it converges).
///
/// docs/localization-state.md gives the measurements behind the bound: at the true pose the
/// misfit of every shared log with reference poses and of the DIS and ROS 2 recordings stays
/// below it on every update; on Wean (a map drawn years before its log, doors closed) it is
/// above it on 4 % of the updates; with another building's map it is above it on 84-100 %.

#include <cstdint>

namespace mote {

/// The filter's verdict after an update.
enum class LocalizationState : std::uint8_t {
  kTracking,   ///< the scans fit the belief and the belief has one settled hypothesis
  kUncertain,  ///< the scans fit, but the belief is spread over several places
  kLost,       ///< the scans do not fit where the belief is
};

/// Its name in reports: "tracking", "uncertain", "lost".
[[nodiscard]] const char* name_of(LocalizationState state) noexcept;

/// How the state is decided.
struct LocalizationStateConfig {
  /// Rate of the exponential average of the misfit: each update moves it this share of the way
  /// to the new scan's (about the last 1 / rate updates count).
  double smoothing = 0.3;
  /// The smoothed misfit above which the filter is lost (see the file comment), until the
  /// control chart below has learned this map and laser.
  double lost_misfit = 0.6;
  /// The control chart (Shewhart's limits on the smoothed misfit, as in Roberts' EWMA chart):
  /// from the smoothed misfits of settled tracking below lost_misfit, once there are
  /// chart_min_updates of them, lost is above mean + chart_sigmas sd, within [lost_misfit,
  /// chart_ceiling * lost_misfit]. A map drawn with its glass or doors closed, or outdoors among
  /// vegetation, fits worse everywhere at the true pose than a clean map does; the bound then
  /// moves up by what that map and laser show while surely tracking. false: lost_misfit only.
  bool learn = true;
  double chart_sigmas = 3.0;
  /// The most the chart may raise the bound, as a factor on lost_misfit. A run that tracks
  /// through clean rooms (misfit 0.1) and a glassy wing (0.55) has a wide spread, and its limit
  /// would pass 0.9: a scan matched 1-3 m from the true pose sees through 0.38-0.52 of its
  /// beams alone (medians on the shared logs, docs/localization-state.md), its misses on top,
  /// and a wrong map would never read lost again. The learned bounds measured are 0.63-0.72.
  double chart_ceiling = 4.0 / 3.0;
  /// Points before the chart's limits are used: Montgomery's 20-25 samples for a chart's
  /// trial limits (Introduction to Statistical Quality Control, ch. 6).
  int chart_min_updates = 25;
};

/// The smoothed misfit and the state it gives.
class LocalizationMonitor {
 public:
  explicit LocalizationMonitor(LocalizationStateConfig config = {}) : config_(config) {}

  /// One update's see-through and hit shares (at the refined best pose) and whether the belief
  /// is one place: hypotheses narrower than the scan reaches hold most of its weight (the
  /// Localizer's focus rule of weight and spread, at the scan's scale: a fresh global set, one
  /// connected cluster the size of the building, is not); a NaN share (no reading with an
  /// endpoint) leaves the state as it was.
  LocalizationState update(double see_through, double hit_share, bool one_place) noexcept;
  /// Forgets the average and the state (after a re-localization): the next scan starts both
  /// afresh, and until then the state is uncertain. The chart stays: it describes the map and
  /// the laser, not where the belief is.
  void reset() noexcept {
    started_ = false;
    smoothed_ = 0.0;
    settling_ = 0;
    tracking_run_ = 0;
    state_ = LocalizationState::kUncertain;
  }
  /// reset(), and the chart too (a new initialization starts from nothing learned).
  void forget() noexcept { *this = LocalizationMonitor(config_); }
  /// reset(), and no `tracking` before the average has seen its window (ceil(1 / smoothing)
  /// updates): after a re-localization, one scan that fits a fresh place read `tracking` at a
  /// wrong place 2 m from the kidnapped Intel robot, and the summary counted that place as
  /// where the re-localization settled.
  void reset_after_relocalization() noexcept;

  [[nodiscard]] double smoothed() const noexcept { return smoothed_; }
  /// The smoothed misfit above which the state is lost: lost_misfit, or the chart's limit once
  /// learned and above it.
  [[nodiscard]] double lost_bound() const noexcept;
  [[nodiscard]] LocalizationState state() const noexcept { return state_; }
  [[nodiscard]] const LocalizationStateConfig& config() const noexcept { return config_; }

 private:
  void learn() noexcept;
  [[nodiscard]] int window() const noexcept;  // ceil(1 / smoothing) updates

  LocalizationStateConfig config_;
  double smoothed_ = 0.0;
  bool started_ = false;
  int settling_ = 0;      // updates before `tracking` is possible again
  int tracking_run_ = 0;  // updates in a row tracking
  LocalizationState state_ = LocalizationState::kUncertain;
  // The chart's points (Welford's running mean and sum of squared deviations).
  double chart_n_ = 0.0;
  double chart_mean_ = 0.0;
  double chart_m2_ = 0.0;
};

}  // namespace mote
