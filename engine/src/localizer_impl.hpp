#pragma once
// The Localizer's state and the steps of one update (private to mote::engine).

#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "blocked_beams.hpp"
#include "map_field.hpp"
#include "mote/engine/beam_model.hpp"
#include "mote/engine/beams.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/hypothesis_hold.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/likelihood_field_model.hpp"
#include "mote/engine/localization_state.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/engine/motion.hpp"
#include "mote/engine/odometry_noise.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/recovery.hpp"
#include "mote/engine/relocalization.hpp"
#include "mote/engine/scan_match.hpp"

namespace mote {

// Why the scan's geometry cannot be used (non-finite angles, NaN range limits or sensor pose),
// or empty when it can.
[[nodiscard]] std::string scan_geometry_problem(const LaserScan& scan);

using SensorVariant = std::variant<LikelihoodFieldModel, BeamModel>;
using MotionVariant = std::variant<OdometryModel, OmniModel, AckermannModel>;

// The motion model a config asks for (localizer_steps.cpp).
[[nodiscard]] MotionVariant make_motion(const LocalizerConfig& c);

// A log Bayes factor below this is "very strong" evidence against a hypothesis (2 ln B < -10 on
// Kass and Raftery's scale, J. Am. Stat. Assoc. 90, 1995): where the scans have told two places
// apart (place_draw.cpp, keep_places.cpp). Read on the filter's tempered likelihoods, the
// evidence its weights carry: a scan's readings are not independent, and the untempered
// product of their likelihoods overstates what one scan says by the tempering's factor.
inline constexpr double kVeryStrongEvidence = -5.0;

struct Localizer::Impl {
  Impl(std::shared_ptr<const OccupancyGrid> grid, LocalizerConfig cfg);

  // Steps of update(), in order (localizer_steps.cpp).
  bool reject(UpdateOutcome outcome, std::string reason);
  // Selects the beams; returns why they cannot be weighed, or empty when they can.
  [[nodiscard]] std::string select(const LaserScan& scan);
  void select_endpoints(const LaserScan& scan);  // readings and endpoints, once it will run
  [[nodiscard]] bool moved_enough(const Pose2& odometry) const;
  [[nodiscard]] bool jumped(const Pose2& odometry) const;
  bool reset_odometry(const Pose2& odometry);
  void run_filter(const Pose2& odometry);  // motion .. estimate, in the executor
  void predict(const Pose2& odometry);
  void drop_blocked_beams();  // unmapped_obstacle_filter, at the predicted particles
  void weigh();
  void temper();
  void normalize();
  void maybe_resample();
  void maybe_inject();
  // Re-localization (relocalize.cpp): counts lost updates after judge_localization(), and
  // before the next motion step widens the belief by a global set when the count calls for it.
  void count_lost_updates();
  void maybe_relocalize();
  void reset_relocalization(bool settled);
  // A local search's particle count for a disc of `radius` m (global_particles_per_bin's).
  [[nodiscard]] std::size_t local_count(double radius) const;
  // Whether a lost filter runs this scan although the robot has not moved (kStillScans).
  [[nodiscard]] bool still_update_due(const LaserScan& scan);
  void update_estimate();
  // Whether the estimate's clusters are focused (BlockedBeamFilter::focused), judged once per
  // update: the re-localization schedule, the blocked-beam filter and tracking tempering all
  // read this one verdict; the state reads the same rule at the scan's scale (one_place).
  void judge_focus();
  // Folds a trusted match's residual correlation into `correlation`.
  void learn_correlation(const ScanMatch& match);
  // The best hypothesis matched to the map with every valid reading, and the state it gives.
  void judge_localization();
  // After an update: the residual of the estimate's motion against the odometry's, and the
  // motion model refitted from the residuals so far.
  void adapt_motion_noise(const Pose2& odometry);
  // After judge_localization(): keeps the reported pose on the place the filter tracked while a
  // hypothesis elsewhere challenges it, until the challenger wins (hypothesis_hold.hpp).
  void hold_reported_place(const Pose2& odometry);
  void hold_report(const ScanMatch& at_held);  // reports the held place, at best uncertain
  // After update_estimate() (keep_places.cpp): a place of the previous update whose cluster
  // fell below a tenth of the belief while the scans have not refuted it (refuted()) is
  // raised back to a tenth (raise_places), so that look-alike places are not resampled away
  // by the luck of a few hundred particles (the places are judge_focus()'s place_anchors).
  void keep_places(const Pose2& odometry);
  // The best place matched to the scan, and the scan's log-likelihood there (keep_places).
  struct BestFit {
    Pose2 pose;
    double log_likelihood = 0.0;
  };
  [[nodiscard]] BestFit fit_best(const PoseEstimate& best) const;
  // Whether the scans refute `place` (a cluster at one of the belief's places) against the
  // best, adding this scan's evidence; `fallen`: below a tenth of the belief (keep_places.cpp).
  bool refuted(const PoseEstimate& place, const BestFit& best, const Pose2& moved, bool fallen);
  void forget_places(const Pose2& moved);  // after keep_places: carries and drops evidence
  // This scan's log-likelihood at one pose, untempered, as weigh() gave the particles.
  [[nodiscard]] double scan_log_likelihood(const Pose2& pose) const;
  // Raises the fallen places to a tenth together (one raise lowers every other place).
  bool raise_places(const std::vector<const PoseEstimate*>& fallen);
  // The resampling, with each of the previous update's places (carried by the odometry) that
  // this scan did not decisively refute drawn with the same particle count and its weight kept
  // (place_draw.cpp): a place is not starved because the luck of its few lowered its weight.
  // place_prior() runs before the scan is weighed, resample_by_place() in place of the draw.
  void place_prior(const Pose2& odometry);
  void weigh_places();  // after the scan's weights: place_weight, place_log_bayes
  void resample_by_place(const KldConfig& per_place);
  void label_places();  // place_label: the index in even_places or none
  [[nodiscard]] std::vector<double> place_weights() const;  // per place, then the rest's
  void scale_by_place(const std::vector<double>& factor);   // weights times factor[label]
  // The scan matched from `start` (the start itself when the match does not converge).
  [[nodiscard]] Pose2 fitted(const Pose2& start) const;

  // Initialization (localizer.cpp): forget everything but the map and the config.
  void start_fresh(bool settled);                  // settled: around a given pose, not a global set
  [[nodiscard]] std::size_t global_count() const;  // global_particles_per_bin's count
  [[nodiscard]] double free_bins() const;          // KLD bins of free space
  void keep_kld_prefix();  // cut a fresh i.i.d. set to the KLD count of its prefix

  LocalizerConfig config;
  std::shared_ptr<const OccupancyGrid> map_owner;  // shared with the caller, or a copy
  const OccupancyGrid& map;
  Executor executor;
  MotionVariant motion;
  std::unique_ptr<SensorVariant> sensor;  // built inside the executor's arena
  BeamSelection selection;
  KldConfig kld;
  KldBins bins;
  AugmentedMcl recovery;
  std::unique_ptr<MapField> field;       // built inside the executor's arena
  std::unique_ptr<ScanMatcher> matcher;  // on field->signed_field
  LocalizationMonitor monitor;
  BlockedBeamFilter blocked_filter;
  OdometryNoiseEstimator odometry_noise;
  ScanMatch last_fix;        // the refined best pose after the previous update
  PoseSummarizer summarize;  // keeps its scratch memory between updates
  ParticleStore store;
  BeamSet beams;
  BeamSet readings;               // every valid reading with an endpoint (the matcher's)
  std::vector<Point2> endpoints;  // their endpoints in the robot frame
  double scan_range = 0.0;        // their mean range (0 when none): the scale of places
  std::vector<float> loglik;      // untempered scan log-likelihood per particle (padded)
  LocalizationEstimate estimate;
  UpdateStats stats;

  std::uint64_t step = 0;  // filter updates run; keys the random streams
  bool initialized = false;
  bool has_odometry = false;
  bool degenerate = false;  // the last scan explained no particle
  Pose2 last_odometry;
  std::uint64_t updates_since_resample = 0;  // 64 bits: no wrap on a live run of years
  RelocalizationSchedule schedule;           // when a lost filter re-localizes
  bool relocalize_due = false;               // re-localize before the next motion step
  bool relocalize_locally = false;           // ... by a local search (count_lost_updates)
  std::uint64_t still_scans = 0;             // scans in a row without motion while lost
  bool force_update = false;  // the next update runs without motion (force_next_update)
  // The verdict of judge_focus() on the clusters of estimate: made after each update's estimate
  // (where the state reads it) and held for the next update's blocked-beam filter and tempering,
  // which weigh against that same belief; made before the first update after initialization.
  bool focused = false;
  // The same judgement at the scale of the scan (BlockedBeamFilter::places_on): the state's
  // test of one hypothesis at one place, which a cloud widened by tempering still passes.
  bool one_place = false;
  std::size_t belief_places = 0;     // places_on()'s count, for the next update's resampling
  std::vector<Pose2> place_anchors;  // places_on()'s anchors, for keep_places and the filter
  // The evidence against each place beside the best (keep_places): where it was, the
  // tempered log likelihood ratio against the best summed over its scans, the verdict, and
  // whether it was judged this update.
  struct PlaceEvidence {
    Pose2 place;
    double log_ratio = 0.0;
    bool refuted = false;
    bool seen = false;
  };
  std::vector<PlaceEvidence> place_evidence;
  // The places of this update for resample_by_place (empty: the plain draw), each particle's
  // place among them, and their weights before the scan was weighed.
  std::vector<Pose2> even_places;
  std::vector<std::uint8_t> place_label;
  std::vector<double> prior_place_weight;
  std::vector<double> place_weight;     // after the scan (and the rest's, last)
  std::vector<double> place_log_bayes;  // the scan's log Bayes factor against the best place
  bool focus_judged = false;            // false between initialization and the first judge_focus()
  // Running geometric mean of ScanMatch::correlation over the matches taken while tracking
  // (learn_correlation), by which the next match's covariance is inflated; 0 until the first,
  // which then inflates by its own.
  double correlation = 0.0;
  // The place last reported (the refined pose after the previous update), once the filter has
  // tracked since initialization; what a challenger must out-explain (hold_reported_place).
  bool has_held = false;
  Pose2 held;
  HypothesisHold hold;
};

}  // namespace mote
