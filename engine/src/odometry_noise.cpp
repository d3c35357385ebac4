#include "mote/engine/odometry_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "mote/engine/kld.hpp"

namespace mote {
namespace {

// Table 5.6, lines 2-4, with amcl's reading of a backward step as a small rotation.
struct Increments {
  double rot1_sq;
  double trans_sq;
  double rot2_sq;
};

double small_rotation(double rot) {
  return std::min(std::abs(rot), std::abs(wrap_angle(rot - std::numbers::pi)));
}

Increments increments_of(const Pose2& step) {
  const double trans = std::hypot(step.x, step.y);
  const double rot1 = trans < 0.01 ? 0.0 : std::atan2(step.y, step.x);
  const double r1 = small_rotation(rot1);
  const double r2 = small_rotation(wrap_angle(step.theta - rot1));
  return {r1 * r1, trans * trans, r2 * r2};
}

}  // namespace

OdometryNoiseEstimator::OdometryNoiseEstimator(OdometryNoiseConfig config)
    : config_(config), lower_z_(standard_normal_quantile(1.0 - config.confidence)) {}

void OdometryNoiseEstimator::Fit::add(double u, double v, double e2, double y,
                                      double keep) noexcept {
  ue = keep * ue + u * e2;
  ve = keep * ve + v * e2;
  u4 = keep * u4 + u * u * u * u;
  v4 = keep * v4 + v * v * v * v;
  uu = keep * uu + u * u;
  uv = keep * uv + u * v;
  vv = keep * vv + v * v;
  uy = keep * uy + u * y;
  vy = keep * vy + v * y;
}

void OdometryNoiseEstimator::Fit::solve(double& p, double& q) const noexcept {
  // Least squares with p, q >= 0: the unconstrained solution when it is feasible, else the
  // better of the two one-term fits (the constrained optimum lies on a boundary).
  const double det = uu * vv - uv * uv;
  if (det > 1e-12 * (uu * vv) && det > 0.0) {
    p = (vv * uy - uv * vy) / det;
    q = (uu * vy - uv * uy) / det;
    if (p >= 0.0 && q >= 0.0) return;
  }
  const double p_only = uu > 0.0 ? std::max(0.0, uy / uu) : 0.0;
  const double q_only = vv > 0.0 ? std::max(0.0, vy / vv) : 0.0;
  // Residual sums of squares up to the common y^2 term: -p uy for p alone, -q vy for q alone.
  if (p_only * uy >= q_only * vy) {
    p = p_only;
    q = 0.0;
  } else {
    p = 0.0;
    q = q_only;
  }
}

bool OdometryNoiseEstimator::add(const Pose2& odom_before, const Pose2& odom_after,
                                 const Pose2& estimate_before, const Pose2& estimate_after,
                                 const FixUncertainty& fix) noexcept {
  const Pose2 odom = between(odom_before, odom_after);
  const Pose2 moved = between(estimate_before, estimate_after);
  const double e_theta = wrap_angle(moved.theta - odom.theta);
  const double e_xy = std::hypot(moved.x - odom.x, moved.y - odom.y);
  if (!std::isfinite(e_theta) || !std::isfinite(e_xy)) return false;
  const Increments inc = increments_of(odom);
  const double rot_sq = inc.rot1_sq + inc.rot2_sq;
  // The gate: the variance the noise so far and the fixes' uncertainty predict (table 5.6).
  const OdometryAlphas a = noise();
  const double noise_rot = a.alpha1 * rot_sq + a.alpha2 * 2.0 * inc.trans_sq;
  const double noise_xy = a.alpha3 * inc.trans_sq + a.alpha4 * rot_sq;
  const double k2 = config_.gate_sigmas * config_.gate_sigmas;
  if (e_theta * e_theta > k2 * (noise_rot + fix.rotation) ||
      e_xy * e_xy > k2 * (noise_xy + fix.translation)) {
    return false;
  }
  // A fix less certain than the odometry tells little about the odometry (along a corridor the
  // scan fixes the heading and the lateral position, not the distance travelled): that part of
  // the residual is left out rather than read as noise.
  const double keep = config_.forgetting;
  const bool rotation_told = fix.rotation <= noise_rot;
  const bool translation_told = fix.translation <= noise_xy;
  const double e2_rot = e_theta * e_theta;
  const double e2_xy = e_xy * e_xy;
  if (rotation_told) rotation_.add(rot_sq, 2.0 * inc.trans_sq, e2_rot, e2_rot - fix.rotation, keep);
  if (translation_told)
    translation_.add(inc.trans_sq, rot_sq, e2_xy, e2_xy - fix.translation, keep);
  if (!rotation_told && !translation_told) return false;
  samples_ = keep * samples_ + 1.0;
  return true;
}

OdometryAlphas OdometryNoiseEstimator::noise() const noexcept {
  if (samples_ < config_.min_samples) return config_.prior;
  OdometryAlphas a;
  rotation_.solve(a.alpha1, a.alpha2);
  translation_.solve(a.alpha3, a.alpha4);
  return a;
}

double OdometryNoiseEstimator::upper_factor(double count) const noexcept {
  // A variance estimated from n residuals: n s^2 / sigma^2 ~ chi^2(n), so sigma^2 <= s^2 n /
  // chi^2_{1-confidence}(n) with the given confidence (the quantile by Wilson and Hilferty, as
  // KLD's). Below two residuals' worth no bound: the approximation is poor there, and one
  // residual that happens to be near zero would vouch for no noise at all.
  constexpr double kNone = std::numeric_limits<double>::infinity();
  if (!(count >= 2.0)) return kNone;
  const double quantile = chi_square_quantile(count, lower_z_);
  return quantile > 0.0 ? count / quantile : kNone;
}

std::optional<OdometryAlphas> OdometryNoiseEstimator::alphas() const noexcept {
  const auto bounded = [&](double alpha) {
    return std::clamp(config_.safety * alpha, config_.alpha_min, config_.alpha_max);
  };
  if (samples_ >= config_.min_samples) {
    const OdometryAlphas a = noise();
    return OdometryAlphas{bounded(a.alpha1), bounded(a.alpha2), bounded(a.alpha3),
                          bounded(a.alpha4)};
  }
  // Before min_samples a term leaves the prior only for the upper confidence bound of the most
  // it can be: the fit of that term alone (in the joint fit the other term takes a share, and
  // from a few residuals the least squares may give it all to one of them). The bound is on
  // the residuals' whole variance; the fixes' share (ue - uy) is known and comes off after it.
  bool answered = false;
  const auto vouched = [&](double ue, double uy, double uu, double count, double prior) {
    const double factor = upper_factor(count);
    const double alone = std::max(0.0, (factor * ue - (ue - uy)) / uu);
    const double upper = config_.safety * alone;
    if (!std::isfinite(factor) || !(upper < prior)) return prior;
    answered = true;
    return bounded(alone);
  };
  const OdometryAlphas& prior = config_.prior;
  const Fit& r = rotation_;
  const Fit& t = translation_;
  const OdometryAlphas a{vouched(r.ue, r.uy, r.uu, r.count_u(), prior.alpha1),
                         vouched(r.ve, r.vy, r.vv, r.count_v(), prior.alpha2),
                         vouched(t.ue, t.uy, t.uu, t.count_u(), prior.alpha3),
                         vouched(t.ve, t.vy, t.vv, t.count_v(), prior.alpha4)};
  if (!answered) return std::nullopt;
  return a;
}

}  // namespace mote
