// The odometry model's alphas by maximum likelihood from odometry increments against the
// motion they stood for (Thrun et al., Probabilistic Robotics, section 5.4: the density of
// table 5.5 with the variances of table 5.6, lines 5-7), linearized around the odometry.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
constexpr double kPoseVarMax = 0.05;
constexpr double kBiasMax = 0.5;
constexpr std::size_t kMinSamples = 30;
constexpr int kEvaluations = 20000;

// amcl's folding of a relative rotation (motion.cpp): driving backwards is a small rotation.
double fold(double rot) { return std::min(std::abs(rot), std::abs(wrap_angle(rot - std::numbers::pi))); }

// -log N(r; mean, v) up to the constant.
double nll1(double r, double mean, double v) { return 0.5 * ((r - mean) * (r - mean) / v + std::log(v)); }

// -log of the bivariate normal of (lateral, theta) with covariance [[a, c], [c, b]].
double nll2(double x, double y, double a, double b, double c) {
  const double det = std::max(a * b - c * c, 1e-300);
  return 0.5 * ((b * x * x - 2 * c * x * y + a * y * y) / det + std::log(det));
}

struct DiffParams {
  double a1, a2, a3, a4, pose_xy, pose_theta, bias_t, bias_r;
};

// Table 5.6's three independent noises n1 (rot1), n2 (trans), n3 (rot2), seen in the motion's
// direction of travel: along = n2, direction = n1, theta = n1 + n3, with
// the variances at the motion (table 5.5); the pose noise adds to each. Odometry that scales
// the motion by (1 + bias) shifts the means by bias times the motion.
double diff_nll(const std::vector<MotionResidual>& rs, const DiffParams& p) {
  double sum = 0;
  for (const MotionResidual& r : rs) {
    const double t = r.trans, r1 = r.rot1, r2 = r.rot2;
    const double v1 = p.a1 * r1 * r1 + p.a2 * t * t;
    const double v2 = p.a3 * t * t + p.a4 * (r1 * r1 + r2 * r2);
    const double v3 = p.a1 * r2 * r2 + p.a2 * t * t;
    const double along_mean = p.bias_t * t;
    const double direction_mean = p.bias_r * r.rot1_signed;
    const double theta_mean = p.bias_r * r.rot;
    sum += nll1(r.along, along_mean, v2 + p.pose_xy);
    if (t < 0.01) {  // no direction of travel (rot1 = 0): the heading alone
      sum += nll1(r.theta, theta_mean, v1 + v3 + p.pose_theta);
      continue;
    }
    // (direction error, heading error) = (n1, n1 + n3): covariance [[v1, v1], [v1, v1 + v3]],
    // the pose noise entering the direction as position noise over the distance.
    sum += nll2(r.direction - direction_mean, r.theta - theta_mean, v1 + p.pose_xy / (t * t),
                v1 + v3 + p.pose_theta, v1);
  }
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
    sum += nll1(r.lateral, bias_r * r.trans * r.rot1_signed, a[0] * rot2 + a[4] * t2 + a[5]);
    sum += nll1(r.theta, bias_r * r.rot, a[3] * rot2 + a[1] * t2 + a[6]);
  }
  return sum;
}

DiffParams diff_from(const std::vector<double>& v, bool with_bias) {
  return {v[0], v[1], v[2], v[3], v[4], v[5], with_bias ? v[6] : 0.0, with_bias ? v[7] : 0.0};
}

std::vector<detail::Bounded> diff_bounds(bool with_bias) {
  std::vector<detail::Bounded> b(4, {0.05, kAlphaMin, kAlphaMax});
  b.push_back({1e-4, kPoseVarMin, kPoseVarMax});
  b.push_back({1e-4, kPoseVarMin, kPoseVarMax});
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

MotionResidual motion_residual(const MotionSample& s) {
  // Table 5.5 evaluates the noise at the motion (its delta-hat, from x_{t-1} and x_t), so the
  // residuals are taken in the motion's direction of travel and its terms are the motion's.
  const Pose2& m = s.motion;
  MotionResidual r;
  r.trans = std::hypot(m.x, m.y);
  r.rot1_signed = r.trans < 0.01 ? 0.0 : std::atan2(m.y, m.x);  // amcl: no rot1 below 1 cm
  const double rot2 = wrap_angle(m.theta - r.rot1_signed);
  r.rot1 = fold(r.rot1_signed);
  r.rot2 = fold(rot2);
  r.rot = m.theta;
  const double c = std::cos(r.rot1_signed), sn = std::sin(r.rot1_signed);
  const Pose2& o = s.odometry;
  r.along = c * o.x + sn * o.y - r.trans;
  r.lateral = -sn * o.x + c * o.y;
  r.theta = wrap_angle(o.theta - m.theta);
  // atan, not atan2: odometry that reports a short step backwards still has the angle n1.
  const double forward = r.trans + r.along;
  r.direction = std::abs(forward) > 1e-12 ? std::atan(r.lateral / forward) : 0.0;
  return r;
}

OdometryFit fit_odometry_noise(const std::vector<MotionSample>& samples) {
  if (samples.size() < kMinSamples) {
    throw Error("odometry fit: " + std::to_string(samples.size()) +
                " increments between updates, at least " + std::to_string(kMinSamples) + " needed");
  }
  std::vector<MotionResidual> rs;
  rs.reserve(samples.size());
  for (const MotionSample& s : samples) rs.push_back(motion_residual(s));

  OdometryFit fit;
  int evals = 0;
  const DiffParams start{0.2, 0.2, 0.2, 0.2, 1e-4, 1e-4, 0, 0};  // mote's defaults
  fit.quality.samples = rs.size();
  fit.quality.log_likelihood_before = -diff_nll(rs, start);

  const std::vector<double> biased = detail::minimize(
      [&](const std::vector<double>& v) { return diff_nll(rs, diff_from(v, true)); },
      diff_bounds(true), kEvaluations, evals);
  const DiffParams p = diff_from(biased, true);
  if (std::getenv("CAL_DEBUG")) {
    std::fprintf(stderr, "nll fit %.3f truth %.3f evals %d\n", diff_nll(rs, p),
                 diff_nll(rs, {0.05, 0.01, 0.02, 0.005, p.pose_xy, p.pose_theta, 0, 0}), evals);
  }
  fit.alphas = {p.a1, p.a2, p.a3, p.a4};
  fit.pose_variance_xy = p.pose_xy;
  fit.pose_variance_theta = p.pose_theta;
  fit.translation_bias = p.bias_t;
  fit.rotation_bias = p.bias_r;
  fit.quality.iterations = evals;

  const std::vector<double> zero = detail::minimize(
      [&](const std::vector<double>& v) { return diff_nll(rs, diff_from(v, false)); },
      diff_bounds(false), kEvaluations, evals);
  fit.alphas_zero_mean = {zero[0], zero[1], zero[2], zero[3]};
  fit.quality.log_likelihood_after = -diff_nll(rs, diff_from(zero, false));
  fit.quality.iterations += evals;
  note_bounds(fit.quality, "", {zero[0], zero[1], zero[2], zero[3]});

  std::vector<detail::Bounded> ob(5, {0.05, kAlphaMin, kAlphaMax});
  ob.push_back({1e-4, kPoseVarMin, kPoseVarMax});
  ob.push_back({1e-4, kPoseVarMin, kPoseVarMax});
  const std::vector<double> omni = detail::minimize(
      [&](const std::vector<double>& v) { return omni_nll(rs, v, p.bias_t, p.bias_r); }, ob,
      kEvaluations, evals);
  fit.alphas_omni = {omni[0], omni[1], omni[2], omni[3]};
  fit.alpha5 = omni[4];
  return fit;
}

}  // namespace mote::replay
