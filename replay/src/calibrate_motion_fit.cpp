// The odometry model's alphas by maximum likelihood from odometry increments against the
// motion they stood for (Thrun et al., Probabilistic Robotics, section 5.4: the density of
// table 5.5 with the variances of table 5.6, lines 5-7), linearized around the odometry.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "calibrate_minimize.hpp"
#include "mote/core/error.hpp"
#include "mote/replay/calibrate.hpp"

namespace mote::replay {
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

// amcl's folding of a relative rotation (motion.cpp): driving backwards is a small rotation.
double fold(double rot) {
  return std::min(std::abs(rot), std::abs(wrap_angle(rot - std::numbers::pi)));
}

// -log N(r; mean, v) up to the constant.
double nll1(double r, double mean, double v) {
  return 0.5 * ((r - mean) * (r - mean) / v + std::log(v));
}

struct DiffParams {
  double a1, a2, a3, a4, pose_xy, pose_theta, bias_t, bias_r, pose_lateral;
  bool direction_bias = true;  ///< see diff_sample
};

struct SampleFit {
  double nll = 0;
  double worst = 0;  ///< largest squared Mahalanobis distance of its parts (chi-square scale)
};

SampleFit diff_sample(const MotionResidual& r, const DiffParams& p) {
  const double t = r.trans, r1 = r.rot1, r2 = r.rot2;
  const double v1 = p.a1 * r1 * r1 + p.a2 * t * t;
  const double v2 = p.a3 * t * t + p.a4 * (r1 * r1 + r2 * r2);
  const double v3 = p.a1 * r2 * r2 + p.a2 * t * t;
  const double along = r.along - p.bias_t * t;
  const double theta = r.theta - p.bias_r * r.rot;
  SampleFit f;
  const double va = v2 + p.pose_xy + r.pose_along;
  f.nll = 0.5 * (along * along / va + std::log(va));
  f.worst = along * along / va;
  if (!r.has_direction) {  // no direction of travel (rot1 = 0): the heading alone
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
  const double dir = r.direction - (p.direction_bias ? p.bias_r * r.rot1_signed : 0.0);
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

DiffParams diff_from(const std::vector<double>& v, bool with_bias, bool direction_bias) {
  return {
      v[0], v[1],          v[2], v[3], v[4], v[5], with_bias ? v[7] : 0.0, with_bias ? v[8] : 0.0,
      v[6], direction_bias};
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

}  // namespace

MotionResidual motion_residual(const MotionSample& s, double min_travel) {
  // Table 5.5 evaluates the noise at the motion (its delta-hat, from x_{t-1} and x_t), so the
  // residuals are taken in the motion's direction of travel and its terms are the motion's.
  const Pose2& m = s.motion;
  MotionResidual r;
  r.trans = std::hypot(m.x, m.y);
  r.rot1_signed = r.trans < min_travel ? 0.0 : std::atan2(m.y, m.x);  // amcl: no rot1 below 1 cm
  r.has_direction = r.trans >= min_travel;
  const double rot2 = wrap_angle(m.theta - r.rot1_signed);
  r.rot1 = fold(r.rot1_signed);
  r.rot2 = fold(rot2);
  r.rot = m.theta;
  const double c = std::cos(r.rot1_signed), sn = std::sin(r.rot1_signed);
  const Pose2& o = s.odometry;
  r.along = c * o.x + sn * o.y - r.trans;
  r.lateral = -sn * o.x + c * o.y;
  r.theta = wrap_angle(o.theta - m.theta);
  // The poses' position covariance seen along (u) and across (v) the motion's direction.
  const double heading = s.heading_before + r.rot1_signed;
  const double ux = std::cos(heading), uy = std::sin(heading);
  auto project = [](const PoseCovariance& cv, double x, double y) {
    return cv.xx * x * x + 2 * cv.xy * x * y + cv.yy * y * y;
  };
  r.pose_along = project(s.before, ux, uy) + project(s.after, ux, uy);
  r.pose_lateral = project(s.before, -uy, ux) + project(s.after, -uy, ux);
  r.pose_theta0 = s.before.tt;
  r.pose_theta1 = s.after.tt;
  // atan, not atan2: odometry that reports a short step backwards still has the angle n1.
  const double forward = r.trans + r.along;
  r.direction = std::abs(forward) > 1e-12 ? std::atan(r.lateral / forward) : 0.0;
  return r;
}

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
  for (const MotionSample& s : samples) rs.push_back(motion_residual(s, min_travel));

  // The negative log-likelihood of the increments kept (rs), with the scale biases fitted and
  // with them held at 0.
  const auto biased_nll = [&](const std::vector<double>& v) {
    return diff_nll(rs, diff_from(v, true, !estimated_poses));
  };
  const auto zero_mean_nll = [&](const std::vector<double>& v) {
    return diff_nll(rs, diff_from(v, false, !estimated_poses));
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
    if (diff_sample(r, diff_from(biased, true, !estimated_poses)).worst < kOutlier)
      kept.push_back(r);
  }
  fit.outliers = rs.size() - kept.size();
  rs = std::move(kept);
  fit.quality.samples = rs.size();
  fit.quality.log_likelihood_before = -diff_nll(rs, start);
  biased = detail::minimize(biased_nll, diff_bounds(true, pose_max), kEvaluations, evals);
  const std::vector<double> se =
      detail::standard_errors(biased_nll, biased, diff_bounds(true, pose_max));
  fit.alphas_se = {se[0], se[1], se[2], se[3]};
  fit.translation_bias_se = se[7];
  fit.rotation_bias_se = se[8];
  const DiffParams p = diff_from(biased, true, !estimated_poses);
  fit.alphas = {p.a1, p.a2, p.a3, p.a4};
  fit.pose_variance_xy = p.pose_xy;
  fit.pose_variance_theta = p.pose_theta;
  fit.translation_bias = p.bias_t;
  fit.rotation_bias = p.bias_r;
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
      [&](const std::vector<double>& v) { return omni_nll(rs, v, p.bias_t, p.bias_r); }, ob,
      kEvaluations, evals);
  fit.alphas_omni = {omni[0], omni[1], omni[2], omni[3]};
  fit.alpha5 = omni[4];
  return fit;
}

}  // namespace mote::replay
