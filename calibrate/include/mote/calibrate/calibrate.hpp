#pragma once
/// \file
/// `mote calibrate`: the sensor and motion model parameters learned from a recorded log
/// (Thrun, Burgard, Fox, Probabilistic Robotics, 2005). With reference poses the fits run once
/// against them; without, the filter's own trajectory stands in for them and localization and
/// fitting alternate until the parameters settle.
///
/// The fits are plain functions of their samples, so they can be checked on draws with known
/// parameters: fit_beam_mixture (table 6.2), fit_likelihood_field (maximum likelihood of
/// table 6.3's mixture) and fit_odometry_noise (maximum likelihood of the increments under
/// table 5.5 / 5.6's model).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/engine/odometry_noise.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/logs/tum.hpp"

namespace mote::calibrate {

/// How a fit went: the data it used and its log-likelihood at the start and at the end.
struct FitQuality {
  std::size_t samples = 0;           ///< beams or odometry increments used
  double log_likelihood_before = 0;  ///< total, at the starting parameters
  double log_likelihood_after = 0;   ///< total, at the fitted parameters
  int iterations = 0;
  std::vector<std::string> at_bound;  ///< parameters that ended on a bound, "name (bound)"
};

// --- beam model (Thrun table 6.1, learned by table 6.2) -----------------------------------

/// The four-part mixture of eqs. 6.4-6.11.
struct BeamMixture {
  double z_hit = 0.7, z_short = 0.1, z_max = 0.1, z_rand = 0.1;
  double sigma_hit = 0.2;     ///< m
  double lambda_short = 0.5;  ///< 1/m
};

/// One beam: the measured range and the range the map predicts at the pose.
struct BeamSample {
  double measured = 0;   ///< m
  double expected = 0;   ///< m, ray cast, <= range_max
  std::size_t scan = 0;  ///< fit_beam_correlation only: which scan the beam is of
  std::size_t slot = 0;  ///< fit_beam_correlation only: its place among the scan's beams
};

struct BeamFit {
  BeamMixture params;
  FitQuality quality;
};

/// Expectation-maximization of table 6.2 over readings in [0, range_max] (range_max = no
/// return). The M-step for lambda_short solves the exact condition of the exponential truncated
/// at z* (eqs. 6.7-6.9) instead of table 6.2's untruncated sum e z, which is biased when lambda
/// z* is not large. Throws Error for fewer than 100 samples.
[[nodiscard]] BeamFit fit_beam_mixture(const std::vector<BeamSample>& samples, double range_max,
                                       BeamMixture start = {});

/// How much the beams of one scan move together, and the likelihood exponent that makes up for
/// it. Neighbouring beams that hit the same wall share its map error (a wall drawn a few cm
/// off, a cluttered shelf), so their range errors are correlated and the product of their
/// likelihoods counts one error many times (Thrun et al., section 6.3.4). The correlation is
/// the autocorrelation rho_k of the range errors of hits (|z - z*| < 3 sigma_hit, both beams
/// of a pair in one scan, k slots apart), summed over the initial positive sequence (lags up
/// to the first whose rho_k + rho_k+1 is not positive, Geyer 1992, and at most half a scan), and
/// the exponent is the ratio of effective to actual beams, tau = 1 / (1 + 2 sum_k rho_k) (the
/// variance inflation of a sum of correlated terms).
struct BeamCorrelation {
  std::vector<double> rho;  ///< rho_1, rho_2, ... up to the last lag summed
  std::size_t pairs = 0;    ///< lag-1 pairs of hits
  double tempering = 1.0;   ///< tau in [0.01, 1]
};

/// Throws Error for fewer than 100 lag-1 pairs of hits.
[[nodiscard]] BeamCorrelation fit_beam_correlation(const std::vector<BeamSample>& samples,
                                                   double range_max, double sigma_hit);

// --- likelihood field (Thrun table 6.3) -------------------------------------------------

struct FieldMixture {
  double z_hit = 0.5, z_rand = 0.5;
  double sigma_hit = 0.2;  ///< m
};

struct FieldFit {
  FieldMixture params;
  FitQuality quality;
};

/// Maximum likelihood of p(d) = z_hit N(d; 0, sigma_hit^2) + z_rand / range_max (table 6.3,
/// lines 7-8) over endpoint distances d (m, clamped as the filter clamps them), z_hit + z_rand
/// = 1, by EM. Throws Error for fewer than 100 samples.
[[nodiscard]] FieldFit fit_likelihood_field(const std::vector<double>& distances, double range_max,
                                            FieldMixture start = {});

// --- odometry (Thrun section 5.4) ---------------------------------------------------------

/// The uncertainty of an estimated pose (m^2, m^2, rad^2; x-y in the map frame).
struct PoseCovariance {
  double xx = 0, xy = 0, yy = 0, tt = 0;
};

/// One odometry increment and the motion it stood for (both robot-frame increments between
/// two filter updates).
struct MotionSample {
  Pose2 odometry;  ///< between(odom_before, odom_after)
  Pose2 motion;    ///< between(pose_before, pose_after)
  /// Known uncertainty of the two poses (zero for a reference), added to the model's variance.
  PoseCovariance before, after;
  double heading_before = 0;  ///< rad, map-frame heading of pose_before (to rotate `before`)
};

/// The odometry model's noise as the fit found it.
struct OdometryFit {
  OdometryAlphas alphas;  ///< diff model (table 5.6), systematic errors removed
  double alpha5 = 0;      ///< omni model's strafe noise; with alphas_omni below
  OdometryAlphas alphas_omni;
  /// Systematic scale errors (odometry = (1 + bias) motion): the filter's models have none, so
  /// the config carries alphas_zero_mean, the noise that covers them too.
  double translation_bias = 0, rotation_bias = 0;
  OdometryAlphas alphas_zero_mean;  ///< diff model fitted with the biases held at 0
  /// Noise floor of the pose source (the filter's own estimates jitter): m^2 per increment
  /// along the motion, rad^2 per pose (each increment gets it twice); about 0 against
  /// reference poses.
  double pose_variance_xy = 0, pose_variance_theta = 0;
  std::size_t outliers = 0;  ///< increments beyond 4 sigma of a first fit, left out
  /// Standard errors (observed information, calibrate_minimize.hpp) of alphas, of the biases
  /// and of alphas_zero_mean: how far the increments pin each down (0: held at a bound).
  OdometryAlphas alphas_se, alphas_zero_mean_se;
  double translation_bias_se = 0, rotation_bias_se = 0;
  FitQuality quality;
};

/// Residuals of one increment in the motion's direction of travel: along, lateral (m) and
/// heading (rad), odometry minus motion, and the motion's noise terms of table 5.6.
struct MotionResidual {
  double along = 0, lateral = 0, theta = 0;
  double direction = 0;  ///< rad, odometry's direction of travel minus the motion's (rot1 error)
  double rot1 = 0, trans = 0, rot2 = 0;  ///< motion's, rot1/rot2 folded as amcl folds them
  double rot1_signed = 0;                ///< motion's rot1, rad, not folded
  double rot = 0;                        ///< motion's total rotation
  bool has_direction = false;            ///< travelled at least min_travel: rot1 is defined
  /// The odometry's own (rot1 - rot2)^2 (backward steps folded, rot1 = 0 below 1 cm), rad^2.
  double split_odometry = 0;
  /// The poses' known variance along and across the motion (both poses, m^2) and in heading
  /// (the first pose's and the second's, rad^2).
  double pose_along = 0, pose_lateral = 0, pose_theta0 = 0, pose_theta1 = 0;
};

/// The residual of one sample (amcl's conventions: rot1 = 0 below min_travel, 1 cm in amcl,
/// backward motion folded).
[[nodiscard]] MotionResidual motion_residual(const MotionSample& s, double min_travel = 0.01);

/// Maximum likelihood of the residuals under the linearized noise of table 5.6 (lines 5-7:
/// var rot1 = alpha1 rot1^2 + alpha2 trans^2, var trans = alpha3 trans^2 + alpha4 (rot1^2 +
/// rot2^2), var rot2 = alpha1 rot2^2 + alpha2 trans^2), with scale biases and a pose-noise floor
/// (up to 1e-3 m^2 and rad^2 for estimated_poses, about 0 otherwise) fitted alongside; and of
/// amcl's omni model on the same residuals. Every alpha is bounded to
/// [1e-5, 2]. Throws Error for fewer than 30 samples.
[[nodiscard]] OdometryFit fit_odometry_noise(const std::vector<MotionSample>& samples,
                                             bool estimated_poses = false);

/// The Ackermann (bicycle) model's noise as the fit found it (AckermannModel, motion.hpp).
struct AckermannFit {
  double alpha_distance = 0;  ///< variance of the arc length per length^2: the config's alpha3
  double alpha_steering = 0;  ///< variance of the steering angle per angle^2: alpha1
  /// The pose source's noise floor as OdometryFit's: m^2 per increment along the motion, rad^2
  /// per pose (0 against a reference).
  double pose_variance_xy = 0, pose_variance_theta = 0;
  std::size_t outliers = 0;  ///< increments beyond 4 sigma of a first fit, left out
  FitQuality quality;        ///< quality.samples: the increments that are arcs, outliers out
};

/// Maximum likelihood of the increments under AckermannModel's density: each increment, of
/// the odometry and of the trajectory, read as an arc (ackermann_arc); the trajectory's arc
/// length and steering angle Gaussian around the odometry's, with variances alpha_distance s^2
/// and alpha_steering phi^2 + the model's steering floor, plus the poses' noise (their known
/// covariance and, for estimated_poses, a fitted floor as in fit_odometry_noise). Increments
/// whose odometry is no arc a car drives (shorter than 1 cm, 5 cm between estimated poses,
/// steered beyond 3/4 of full lock, or not finite) are left out. Throws Error when fewer than
/// 30 remain, before or after the 4-sigma outlier cut.
[[nodiscard]] AckermannFit fit_ackermann_noise(const std::vector<MotionSample>& samples,
                                               double wheelbase, bool estimated_poses = false);

// --- the whole calibration ----------------------------------------------------------------

/// The online odometry noise's margin (LocalizerConfig::motion_noise_margin) is a choice no fit
/// makes: the residuals between the filter's estimates shrink with the weight the scan gets
/// against the odometry, so the variance factor that keeps the cloud wide enough depends on the
/// sensor model, the tempering and the particle count (Intel, calibrated config, 5000
/// particles, seeds 1-3: margin 4 ATE 0.0506 m, 10 0.0486 m, 14 0.0509 m, 16 loses track on
/// seed 1). calibrate() chooses it by how well the scans fit the map at the poses the filter
/// estimates: the mean, over the updates of two tracking runs (the config's seed and the next),
/// of the per-beam mean log-density z_hit N(d; 0, sigma_hit^2) + z_rand / range_max of the
/// endpoints' distances d to the map (table 6.3, the fitted field's parameters), which needs no
/// reference and falls where a track is lost.
struct MarginTrial {
  double margin = 0;      ///< motion_noise_margin tried
  double fit = 0;         ///< mean per-beam log-density at the estimates, nats
  double spread = 0;      ///< half the runs' range (two runs: the standard error of `fit`)
  std::size_t poses = 0;  ///< estimates scored, over both runs
  bool accepted = false;  ///< the search took this step (search_margin)
};

/// The fit of a tracking run with the given margin: MarginTrial without its margin.
using MarginScorer = std::function<MarginTrial(double margin)>;

/// Hill-climbing over margins start * sqrt(2)^k (to three digits) within [min, max]: upward
/// while a step improves the fit by more than the two trials' spreads together (what the runs'
/// disagreement says is noise), then downward from start the same way if the first step up did
/// not. Returns every trial in the order run, the start and the steps taken `accepted`. Throws
/// Error unless 0 < min <= start <= max.
[[nodiscard]] std::vector<MarginTrial> search_margin(const MarginScorer& score, double start,
                                                     double min = 1.0, double max = 64.0);

/// The accepted trial with the highest fit: where the search ended. Throws Error for none.
[[nodiscard]] const MarginTrial& best_margin(const std::vector<MarginTrial>& trials);

/// What calibrate() reports while it runs: which filter run (0-based: the self-calibration
/// rounds first, then the margin search's tracking runs), scans of it done, total.
using CalibrationProgress =
    std::function<void(int round, std::size_t scans_done, std::size_t scans_total)>;

struct CalibrationOptions {
  std::filesystem::path map;        ///< map_server YAML
  std::filesystem::path log;        ///< any log open_scan_log reads
  std::filesystem::path reference;  ///< TUM poses; empty = self-calibration
  LocalizerConfig config;           ///< starting point; fitted values replace its fields
  logs::ReaderOptions reader;
  int beams_per_scan = 90;  ///< beams per scan the sensor fits use, evenly spaced
  /// Self-calibration rounds at most. Each round localizes with the previous round's fit; the
  /// rounds stop once no parameter moves by more than `settle` (relative, weights absolute, the
  /// odometry alphas by the mean relative change of the noise they predict for the log's
  /// increments).
  int max_rounds = 6;
  double settle = 0.1;
  std::size_t min_scans = 50;  ///< fewer scans with motion is "log too short"
  /// Particles of the margin search's tracking runs (min = max); 0 keeps the config's KLD
  /// bounds. The margin that tracks best depends on it: calibrate for the count you will run.
  int particles = 0;
  /// Search the online noise's margin after the rounds (MarginTrial, at least six tracking runs
  /// over the log). Off, the config keeps its margin and CalibrationResult::margins is empty:
  /// for callers that want the fits alone.
  bool search_margin = true;
  CalibrationProgress progress;
};

/// The parameters after one round and how the filter did with the previous ones.
struct CalibrationRound {
  BeamFit beam;
  FieldFit field;
  OdometryFit odometry;
  std::optional<AckermannFit> ackermann;  ///< when the config's odom_model_type is ackermann
  BeamCorrelation correlation;            ///< the scans' beam correlation: the tempering
  std::size_t poses = 0;                  ///< poses the fits used
  double largest_change = 0;              ///< against the previous round (relative)
  std::string largest_change_of;          ///< which parameter
  /// The same per group: the sensor model (sigma_hit, z_hit, tracking_tempering) and the
  /// motion model (the odometry noise, Ackermann's alphas).
  double sensor_change = 0;
  std::string sensor_change_of;
  double motion_change = 0;
  std::string motion_change_of;
};

/// Plot data: the per-beam range error z - z* and the odometry residuals.
struct CalibrationSamples {
  std::vector<BeamSample> beams;
  std::vector<MotionResidual> motion;
  double range_max = 0;
};

/// The fitted config against the one the calibration started from (mote's defaults, or the
/// --config file) on the calibration's own log: one replay with each, the same seed, particle
/// counts and start. `mote calibrate` runs the replays (the replay layer's); the verdict and
/// the config report them, since a fit that settled can still track worse than the defaults.
struct StartComparison {
  /// What was compared: "ate_rmse_m" (m, RMS position error against the reference; lower is
  /// better) or "scan_fit" (without a reference: scan_fit of each run's trajectory, nats;
  /// higher is better).
  std::string metric;
  double fitted = 0;        ///< the metric's value replaying with the fitted config
  double start = 0;         ///< the same with the starting config
  std::string start_name;   ///< "mote's defaults", or the starting config's file
  int min_particles = 0;    ///< of both replays
  int max_particles = 0;    ///< of both replays
  std::uint64_t seed = 0;   ///< of both replays
  std::size_t updates = 0;  ///< updates of the fitted config's replay
  std::size_t start_updates = 0;
};

/// Whether the fitted config did strictly better than the starting one (a tie keeps the start).
[[nodiscard]] bool fitted_is_better(const StartComparison& c);

/// The verdict line on the comparison (without the leading "verdict: "): which config did better
/// on the log, by how much, and which one to run (`fitted_config`: the written config's path).
[[nodiscard]] std::string comparison_verdict(const StartComparison& c,
                                             const std::string& fitted_config);

/// DIR/comparison.yaml's text: the metric, both values, which is better, particles and seed.
[[nodiscard]] std::string comparison_yaml(const StartComparison& c);

struct CalibrationResult {
  LocalizerConfig config;  ///< the starting config with every fitted value in
  LocalizerConfig start;   ///< the starting config (CalibrationOptions::config)
  bool with_reference = false;
  std::size_t scans = 0;  ///< scans in the log
  std::vector<CalibrationRound> rounds;
  bool settled = false;  ///< self-calibration stopped because the parameters settled
  /// The margin search (MarginTrial): tracking runs with the final config from the last round's
  /// first converged estimate (the reference's first pose with --reference); empty when the
  /// config's model does not adapt its noise (adaptive_motion_noise, diff model only) or
  /// CalibrationOptions::search_margin is off.
  std::vector<MarginTrial> margins;
  CalibrationSamples samples;
  double wall_s = 0;
  /// Set by the caller after calibrate() (mote calibrate replays both configs); written to
  /// config.yaml as a comment and to DIR/comparison.yaml by write_calibration.
  std::optional<StartComparison> comparison;
};

/// How well the log's scans fit the map along `trajectory` (a replay's estimates, stamped as
/// the scans they were made at): MarginTrial's score, the mean over the poses of the per-beam
/// mean log-density (nats) of the endpoints under the last round's field, the same for any
/// config, so that runs with different sensor models compare. Reads the map and log again.
[[nodiscard]] double scan_fit(const CalibrationOptions& o, const CalibrationResult& r,
                              const std::vector<logs::StampedPose>& trajectory);

/// Whether one group of fitted parameters (the sensor model, the motion model) settled.
struct GroupVerdict {
  enum class Status {
    kFitOnce,       ///< fitted once against reference poses: no rounds to settle
    kConverged,     ///< the last round moved no parameter by more than `settle`
    kWithinSpread,  ///< moved more, but every alpha within 2 standard errors of both fits
    kNotConverged,  ///< stopped at the round limit while still moving
  };
  std::string group;  ///< "sensor" or "odometry"
  Status status = Status::kFitOnce;
  std::size_t rounds = 0;
  double last_change = 0;  ///< relative (a weight's absolute), as CalibrationRound's
  std::string last_change_of;
  std::vector<std::string> at_bound;  ///< the group's parameters on a bound, "name (bound)"
};

/// The verdict per group on a calibration, with `settle` the threshold the rounds stopped at
/// (CalibrationOptions::settle). docs/calibration.md explains the criteria.
[[nodiscard]] std::vector<GroupVerdict> judge_calibration(const CalibrationResult& result,
                                                          double settle);

/// Reads the log (and reference), fits, and localizes again as needed. Throws Error (one line)
/// for a log too short to fit from, a log without odometry, or a filter that never converges.
[[nodiscard]] CalibrationResult calibrate(const CalibrationOptions& options);

/// Writes DIR/config.yaml (flat amcl names, every value commented with its source),
/// DIR/calibration.png and, with result.comparison, DIR/comparison.yaml. Returns the config path.
/// Throws Error when a file cannot be written.
std::filesystem::path write_calibration(const CalibrationResult& result,
                                        const std::filesystem::path& directory);

/// The config.yaml text alone.
[[nodiscard]] std::string calibration_yaml(const CalibrationResult& result);

/// Draws the range-error histogram with the fitted mixture and the odometry residual scatter
/// with the fitted 1- and 2-sigma bounds into a PNG.
void write_calibration_png(const CalibrationResult& result, const std::filesystem::path& png);

}  // namespace mote::calibrate
