#pragma once
/// \file
/// The odometry model's noise (alpha1..alpha4, Thrun et al. table 5.6 in ROS amcl's convention)
/// estimated online from the filter's own corrections: the motion between successive poses the
/// scans fixed (the scan matcher's refined poses, scan_match.hpp) against the odometry
/// increment between the same updates, less the uncertainty of those poses themselves. Odometry
/// differs by orders of magnitude between robots (a log whose odometry under-reports rotation by a
/// third needs rotation noise that, on a robot with good odometry, lets the estimate drift along a
/// corridor), so no constant serves both; the residuals of each log say which it is.

#include <optional>

#include "mote/core/pose.hpp"

namespace mote {

/// alpha1..alpha4 with amcl's meaning (rotation from rotation, rotation from translation,
/// translation from translation, translation from rotation).
struct OdometryAlphas {
  double alpha1 = 0.2;
  double alpha2 = 0.2;
  double alpha3 = 0.2;
  double alpha4 = 0.2;
};

/// How the residuals become alphas.
struct OdometryNoiseConfig {
  double forgetting = 0.99;  ///< per update: the fit remembers about the last 100 updates
  /// Variance factor on the fitted noise. Spread that merely equals the odometry's error
  /// would let the particles follow the odometry a little too closely, the residuals would
  /// shrink with it and the fit would talk itself down; four times the variance (twice the
  /// standard deviation) keeps a 2-sigma error of the odometry inside the cloud's 1 sigma.
  /// Measured on Intel (no config, 5000 particles): factor 2 ATE 0.0618 m, 4 0.0583 m,
  /// 8 0.0587 m, 16 0.0629 m; the beam model 0.0667 m at 2, 0.0614 m at 4.
  double safety = 4.0;
  double alpha_min = 0.002;  ///< bounds of every fitted alpha
  double alpha_max = 1.0;
  /// Effective samples (after forgetting) after which the fit answers alone. Before that an
  /// alpha leaves the prior only for the upper bound of its confidence interval (below).
  double min_samples = 20.0;
  /// One-sided confidence of the upper bound on each fitted alpha: the fit is read at the top
  /// of its interval, so that a fit from a few residuals is taken only as far as they vouch for
  /// it (Kish's effective count of the residuals that carried the term, a chi-square bound).
  double confidence = 0.95;
  /// The noise assumed until the data vouch for less (the config's alphas): it also sets the
  /// gate below until min_samples.
  OdometryAlphas prior{};
  /// A residual farther than this many standard deviations of what the current fit (or the
  /// prior) and the poses' own uncertainty predict is a jump of the estimate (a cluster
  /// switch, a re-localization), not odometry noise, and is left out.
  double gate_sigmas = 3.0;
};

/// How well the scans fixed the two poses of a residual: the variances of the poses' heading
/// (rad^2) and position (m^2, x plus y) summed over both ends (the scan matcher's covariances).
/// They are subtracted from the squared residual: what is left estimates the odometry's share.
struct FixUncertainty {
  double rotation = 0.0;
  double translation = 0.0;
};

/// Exponentially weighted least squares of the squared residuals, less the poses' own
/// uncertainty, on the model's variance terms (table 5.6, lines 5-7):
/// e_theta^2 - u_rot ~ alpha1 (rot1^2 + rot2^2) + alpha2 2 trans^2 and
/// |e_xy|^2 - u_xy ~ alpha3 trans^2 + alpha4 (rot1^2 + rot2^2), each pair fitted with alphas >= 0.
/// Residuals between the filter's own estimates (the particle mean) would carry the cloud's
/// spread, which grows with the alphas the fit returns: the fit would then chase its own
/// margin. The refined poses depend on the scan and the map only.
class OdometryNoiseEstimator {
 public:
  /// Throws ConfigError unless config.confidence is in (0, 1).
  explicit OdometryNoiseEstimator(OdometryNoiseConfig config = {});

  /// One update's evidence: odometry from odom_before to odom_after while the fixed pose moved
  /// from estimate_before to estimate_after, whose uncertainty is `fix`. Returns false when
  /// the pair was left out (the gate).
  bool add(const Pose2& odom_before, const Pose2& odom_after, const Pose2& estimate_before,
           const Pose2& estimate_after, const FixUncertainty& fix = {}) noexcept;

  /// From min_samples on, safety times the fitted alphas, within [alpha_min, alpha_max]. Before
  /// that, per alpha, safety times the upper confidence bound of its term where that is below
  /// the prior, else the prior; nullopt while every alpha is still the prior.
  [[nodiscard]] std::optional<OdometryAlphas> alphas() const noexcept;
  /// The fitted alphas without the safety factor and bounds, or the prior before min_samples.
  [[nodiscard]] OdometryAlphas noise() const noexcept;

  /// Forgets every residual.
  void reset() noexcept {
    rotation_ = {};
    translation_ = {};
    samples_ = 0.0;
  }

 private:
  // Normal equations of y ~ p u + q v, accumulated with forgetting; y is the squared residual e2
  // less the fixes' share.
  struct Fit {
    double uu = 0, uv = 0, vv = 0, uy = 0, vy = 0;
    double ue = 0, ve = 0;  // sums of u e2, v e2: the bounds before min_samples
    double u4 = 0, v4 = 0;  // sums of u^4, v^4: the effective counts below
    void add(double u, double v, double e2, double y, double keep) noexcept;
    void solve(double& p, double& q) const noexcept;
    // Kish's effective count of the residuals behind each term, (sum w)^2 / sum w^2 with the
    // least-squares weights w = u^2 (a term one turn determined counts once). With forgetting
    // the exact sum w^2 would decay by keep^2; u4 decays by keep, which counts fewer: the
    // wider bound.
    [[nodiscard]] double count_u() const noexcept { return u4 > 0.0 ? uu * uu / u4 : 0.0; }
    [[nodiscard]] double count_v() const noexcept { return v4 > 0.0 ? vv * vv / v4 : 0.0; }
  };

  [[nodiscard]] double upper_factor(double count) const noexcept;

  OdometryNoiseConfig config_;
  double lower_z_;  // the standard normal quantile at 1 - confidence
  Fit rotation_;
  Fit translation_;
  double samples_ = 0.0;
};

}  // namespace mote
