// The odometry model's alphas by maximum likelihood from odometry increments against the
// motion they stood for (Thrun et al., Probabilistic Robotics, section 5.4: the density of
// table 5.5 with the variances of table 5.6, lines 5-7), linearized around the odometry.
#include <algorithm>
#include <cmath>
#include <string>

#include "calibrate_minimize.hpp"
#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"

namespace mote::calibrate {
namespace {

constexpr double kAlphaMin = 1e-5;
constexpr double kAlphaMax = 2.0;
constexpr double kPoseVarMin = 1e-9;  // m^2, rad^2
// Pose noise of a trajectory that scan alignment estimated: up to 3 cm and 1.8 degrees; a
// reference trajectory is taken as exact (the floor would otherwise absorb real noise).
constexpr double kPoseVarMax = 1e-3;
constexpr double kExactPoseVar = 1e-8;
constexpr double kMinTravelEstimated = 0.05;  // m
constexpr double kBiasMax = 0.5;
constexpr std::size_t kMinSamples = 30;
constexpr int kEvaluations = 20000;
constexpr double kOutlier = 16.0;  // squared Mahalanobis distance: 4 sigma

// -log N(r; mean, v) up to the constant.
double nll1(double r, double mean, double v) {
  return 0.5 * ((r - mean) * (r - mean) / v + std::log(v));
}

/// Which poses the increments run between, and which stage of their fit reads them.
enum class DiffStage {
  kExactPoses,  ///< a reference: every channel, the bias in the direction channel too
  /// the filter's poses: no bias in the direction channel (diff_sample), the along channel's
  /// turns from the odometry (along_turns)
  kEstimatedPoses,
  kHeadingOnly,  ///< the filter's poses, direction channel left out (fit_biases_then_alphas)
  kBiasesHeld,   ///< the filter's poses, the biases held and scaling the direction's mean too
};

struct DiffParams {
  double a1, a2, a3, a4, pose_xy, pose_theta, bias_t, bias_r, pose_lateral;
  DiffStage stage = DiffStage::kExactPoses;

  [[nodiscard]] bool direction_bias() const noexcept {
    return stage == DiffStage::kExactPoses || stage == DiffStage::kBiasesHeld;
  }
  [[nodiscard]] bool odometry_turns() const noexcept { return stage != DiffStage::kExactPoses; }
};

struct SampleFit {
  double nll = 0;
  double worst = 0;  ///< largest squared Mahalanobis distance of its parts (chi-square scale)
};

// The turns rot1^2 + rot2^2 that scale alpha4 in the along channel's variance (table 5.6 line
// 6), as ((rot1 + rot2)^2 + (rot1 - rot2)^2) / 2. Between estimated poses the motion's split
// of its rotation into rot1 and rot2 carries the poses' position noise over the distance
// (about 0.1 rad for 1.5 cm over 20 cm): it inflates the turns of straight steps and talks
// alpha4 down (errors in variables: 0.040 for 0.05 on the noisy simulated robot, 1800 s). Its
// sum, the motion's whole rotation, is sure; the split is taken from the odometry instead,
// whose noise n1 - n3 is independent of the along residual n2 and has a known mean: with rot1
// and rot2 scaled by (1 + bias), E[split_odo^2] = ((1 + bias)^2 + alpha1 / 2) split^2 +
// alpha1 rot^2 / 2 + 2 alpha2 trans^2, which is taken back.
double along_turns(const MotionResidual& r, const DiffParams& p) {
  if (!p.odometry_turns()) return r.rot1 * r.rot1 + r.rot2 * r.rot2;
  const double rot2 = r.rot * r.rot, t2 = r.trans * r.trans;
  const double scale = (1 + p.bias_r) * (1 + p.bias_r) + 0.5 * p.a1;
  const double split2 = (r.split_odometry - 0.5 * p.a1 * rot2 - 2 * p.a2 * t2) / scale;
  return 0.5 * (rot2 + split2);
}

SampleFit diff_sample(const MotionResidual& r, const DiffParams& p) {
  const double t = r.trans, r1 = r.rot1, r2 = r.rot2;
  const double v1 = p.a1 * r1 * r1 + p.a2 * t * t;
  const double v2 = p.a3 * t * t + p.a4 * along_turns(r, p);
  const double v3 = p.a1 * r2 * r2 + p.a2 * t * t;
  const double along = r.along - p.bias_t * t;
  const double theta = r.theta - p.bias_r * r.rot;
  SampleFit f;
  // The turns taken back can fall below 0 for a straight step: the variance cannot.
  const double va = std::max(v2 + p.pose_xy + r.pose_along, kPoseVarMin);
  f.nll = 0.5 * (along * along / va + std::log(va));
  f.worst = along * along / va;
  if (!r.has_direction ||
      p.stage == DiffStage::kHeadingOnly) {  // no direction of travel: the heading alone
    const double vt = v1 + v3 + 2 * p.pose_theta + r.pose_theta0 + r.pose_theta1;
    f.nll += 0.5 * (theta * theta / vt + std::log(vt));
    f.worst = std::max(f.worst, theta * theta / vt);
    return f;
  }
  // (direction error, heading error) = (n1, n1 + n3): covariance [[v1, v1], [v1, v1 + v3]].
  // Independent pose errors at both ends (var pose_xy / 2 along the motion, pose_lateral / 2
  // across it: scan alignment in a corridor is surer across it than along; pose_theta in
  // heading) add position noise over the distance to the direction, both headings to the
  // heading, and the first heading to both (it turns the frame the displacement is seen in).
  // Between estimated poses no bias term in the direction: its regressor, the motion's rot1,
  // carries the poses' position noise over the distance, the same noise as the direction error
  // with the opposite sign, and pulls the bias negative (errors in variables); the heading's
  // regressor, the whole rotation, is large against its noise.
  const double dir = r.direction - (p.direction_bias() ? p.bias_r * r.rot1_signed : 0.0);
  const double a = v1 + (p.pose_lateral + r.pose_lateral) / (t * t) + p.pose_theta + r.pose_theta0;
  const double b = v1 + v3 + 2 * p.pose_theta + r.pose_theta0 + r.pose_theta1;
  const double c = v1 + p.pose_theta + r.pose_theta0;
  const double det = std::max(a * b - c * c, 1e-300);
  const double q = (b * dir * dir - 2 * c * dir * theta + a * theta * theta) / det;
  f.nll += 0.5 * (q + std::log(det));
  f.worst = std::max(f.worst, q / 2);
  return f;
}

// Table 5.6's three independent noises n1 (rot1), n2 (trans), n3 (rot2), seen in the motion's
// direction of travel: along = n2, direction = n1, theta = n1 + n3, with the variances at the
// motion (table 5.5); odometry that scales the motion by (1 + bias) shifts the means by bias
// times the motion.
double diff_nll(const std::vector<MotionResidual>& rs, const DiffParams& p) {
  double sum = 0;
  for (const MotionResidual& r : rs) sum += diff_sample(r, p).nll;
  return sum;
}

// amcl's omni model (motion.cpp): along the displacement var alpha3 trans^2 + alpha1 rot^2,
// heading alpha4 rot^2 + alpha2 trans^2, strafe alpha1 rot^2 + alpha5 trans^2, independent.
double omni_nll(const std::vector<MotionResidual>& rs, const std::vector<double>& a, double bias_t,
                double bias_r) {
  double sum = 0;
  for (const MotionResidual& r : rs) {
    const double t2 = r.trans * r.trans;
    const double rot2 = r.rot * r.rot;
    sum += nll1(r.along, bias_t * r.trans, a[2] * t2 + a[0] * rot2 + a[5]);
    sum += nll1(r.lateral, 0.0, a[0] * rot2 + a[4] * t2 + a[5]);
    sum += nll1(r.theta, bias_r * r.rot, a[3] * rot2 + a[1] * t2 + a[6]);
  }
  return sum;
}

// The parameter vector the minimizer moves (alphas, pose variances, pose_lateral, biases) read
// at one stage of the fit (DiffStage).
DiffParams diff_from(const std::vector<double>& v, bool with_bias, DiffStage stage) {
  return {v[0], v[1], v[2], v[3], v[4], v[5], with_bias ? v[7] : 0.0, with_bias ? v[8] : 0.0,
          v[6], stage};
}

std::vector<detail::Bounded> diff_bounds(bool with_bias, double pose_max) {
  std::vector<detail::Bounded> b(4, {0.05, kAlphaMin, kAlphaMax});
  b.push_back({std::sqrt(kPoseVarMin * pose_max), kPoseVarMin, pose_max});
  b.push_back({std::sqrt(kPoseVarMin * pose_max), kPoseVarMin, pose_max});
  b.push_back({std::sqrt(kPoseVarMin * pose_max), kPoseVarMin, pose_max});
  if (with_bias) {
    b.push_back({0.0, -kBiasMax, kBiasMax, false});
    b.push_back({0.0, -kBiasMax, kBiasMax, false});
  }
  return b;
}

void note_bounds(FitQuality& q, const char* model, const std::vector<double>& alphas) {
  for (std::size_t i = 0; i < alphas.size(); ++i) {
    const std::string name = std::string(model) + "alpha" + std::to_string(i + 1);
    if (alphas[i] <= kAlphaMin * 1.05) q.at_bound.push_back(name + " (lower bound 1e-05)");
    if (alphas[i] >= kAlphaMax * 0.95) q.at_bound.push_back(name + " (upper bound 2)");
  }
}

// Between estimated poses the scale biases come from the along and heading channels alone, and
// the alphas from all three channels with the biases held there. The direction channel's
// regressor (the motion's rot1) and table 5.6's variance terms (rot1, rot2) carry the poses'
// position noise over the distance, and a joint fit trades that noise against the rotation
// scale error (errors in variables: +0.01 to +0.04 on the simulated robots, docs/
// calibration.md); the heading's regressor, the whole rotation, is large against the noise.
// Each figure's standard error is that of its own stage.
void fit_biases_then_alphas(const std::vector<MotionResidual>& rs, double pose_max,
                            OdometryFit& fit, int& evals) {
  // Stage 1: no pose_lateral (the direction channel is out).
  const auto heading_nll = [&](const std::vector<double>& h) {
    return diff_nll(rs, diff_from({h[0], h[1], h[2], h[3], h[4], h[5], kPoseVarMin, h[6], h[7]},
                                  true, DiffStage::kHeadingOnly));
  };
  std::vector<detail::Bounded> hb = diff_bounds(true, pose_max);
  hb.erase(hb.begin() + 6);
  int stage_evals = 0;
  const std::vector<double> h = detail::minimize(heading_nll, hb, kEvaluations, stage_evals);
  const std::vector<double> h_se = detail::standard_errors(heading_nll, h, hb);
  fit.translation_bias = h[6];
  fit.rotation_bias = h[7];
  fit.translation_bias_se = h_se[6];
  fit.rotation_bias_se = h_se[7];
  // Stage 2: the biases held, the direction channel's mean scaled by them too (the odometry's
  // rot1 is scaled as its rot2, table 5.6 with a scale error).
  const auto held_nll = [&](const std::vector<double>& w) {
    return diff_nll(rs, diff_from({w[0], w[1], w[2], w[3], w[4], w[5], w[6], h[6], h[7]}, true,
                                  DiffStage::kBiasesHeld));
  };
  const std::vector<detail::Bounded> wb = diff_bounds(false, pose_max);
  const std::vector<double> w = detail::minimize(held_nll, wb, kEvaluations, evals);
  const std::vector<double> w_se = detail::standard_errors(held_nll, w, wb);
  fit.alphas = {w[0], w[1], w[2], w[3]};
  fit.alphas_se = {w_se[0], w_se[1], w_se[2], w_se[3]};
  fit.pose_variance_xy = w[4];
  fit.pose_variance_theta = w[5];
  evals += stage_evals;
}

}  // namespace

OdometryFit fit_odometry_noise(const std::vector<MotionSample>& samples, bool estimated_poses) {
  const double pose_max = estimated_poses ? kPoseVarMax : kExactPoseVar;
  if (samples.size() < kMinSamples) {
    throw Error("odometry fit: " + std::to_string(samples.size()) +
                " increments between updates, at least " + std::to_string(kMinSamples) + " needed");
  }
  std::vector<MotionResidual> rs;
  rs.reserve(samples.size());
  // Between estimated poses a step shorter than a few times their position noise has no
  // direction: its rot1 would be noise, and table 5.6 would read rot1 and rot2 as large turns.
  const double min_travel = estimated_poses ? kMinTravelEstimated : 0.01;
  const DiffStage stage = estimated_poses ? DiffStage::kEstimatedPoses : DiffStage::kExactPoses;
  for (const MotionSample& s : samples) rs.push_back(motion_residual(s, min_travel));

  // The negative log-likelihood of the increments kept (rs), with the scale biases fitted and
  // with them held at 0.
  const auto biased_nll = [&](const std::vector<double>& v) {
    return diff_nll(rs, diff_from(v, true, stage));
  };
  const auto zero_mean_nll = [&](const std::vector<double>& v) {
    return diff_nll(rs, diff_from(v, false, stage));
  };
  OdometryFit fit;
  int evals = 0;
  const DiffParams start{0.2, 0.2, 0.2, 0.2, 1e-4, 1e-4, 0, 0, 1e-4};  // mote's defaults
  fit.quality.samples = rs.size();
  fit.quality.log_likelihood_before = -diff_nll(rs, start);

  std::vector<double> biased =
      detail::minimize(biased_nll, diff_bounds(true, pose_max), kEvaluations, evals);
  // Increments beyond 4 sigma of the first fit are poses the trajectory got wrong (a heading
  // the refinement could not fix), not odometry noise: Gaussian noise puts 1 in 10^4 there, and
  // a few of them move the maximum far. They are left out and the fit repeated.
  std::vector<MotionResidual> kept;
  for (const MotionResidual& r : rs) {
    if (diff_sample(r, diff_from(biased, true, stage)).worst < kOutlier) kept.push_back(r);
  }
  fit.outliers = rs.size() - kept.size();
  rs = std::move(kept);
  fit.quality.samples = rs.size();
  fit.quality.log_likelihood_before = -diff_nll(rs, start);
  if (estimated_poses) {
    fit_biases_then_alphas(rs, pose_max, fit, evals);
  } else {
    biased = detail::minimize(biased_nll, diff_bounds(true, pose_max), kEvaluations, evals);
    const std::vector<double> se =
        detail::standard_errors(biased_nll, biased, diff_bounds(true, pose_max));
    fit.alphas_se = {se[0], se[1], se[2], se[3]};
    fit.translation_bias_se = se[7];
    fit.rotation_bias_se = se[8];
    const DiffParams p = diff_from(biased, true, DiffStage::kExactPoses);
    fit.alphas = {p.a1, p.a2, p.a3, p.a4};
    fit.pose_variance_xy = p.pose_xy;
    fit.pose_variance_theta = p.pose_theta;
    fit.translation_bias = p.bias_t;
    fit.rotation_bias = p.bias_r;
  }
  fit.quality.iterations = evals;

  const std::vector<double> zero =
      detail::minimize(zero_mean_nll, diff_bounds(false, pose_max), kEvaluations, evals);
  fit.alphas_zero_mean = {zero[0], zero[1], zero[2], zero[3]};
  const std::vector<double> zero_se =
      detail::standard_errors(zero_mean_nll, zero, diff_bounds(false, pose_max));
  fit.alphas_zero_mean_se = {zero_se[0], zero_se[1], zero_se[2], zero_se[3]};
  fit.quality.log_likelihood_after = -zero_mean_nll(zero);
  fit.quality.iterations += evals;
  note_bounds(fit.quality, "", {zero[0], zero[1], zero[2], zero[3]});

  std::vector<detail::Bounded> ob(5, {0.05, kAlphaMin, kAlphaMax});
  ob.push_back({std::sqrt(kPoseVarMin * pose_max), kPoseVarMin, pose_max});
  ob.push_back({std::sqrt(kPoseVarMin * pose_max), kPoseVarMin, pose_max});
  const std::vector<double> omni = detail::minimize(
      [&](const std::vector<double>& v) {
        return omni_nll(rs, v, fit.translation_bias, fit.rotation_bias);
      },
      ob, kEvaluations, evals);
  fit.alphas_omni = {omni[0], omni[1], omni[2], omni[3]};
  fit.alpha5 = omni[4];
  return fit;
}

}  // namespace mote::calibrate
