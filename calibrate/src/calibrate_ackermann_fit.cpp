// The Ackermann (bicycle) model's noise by maximum likelihood from odometry increments against
// the motion they stood for: the model (AckermannModel, motion.hpp) reads each increment as one
// arc (s, phi) and draws the true arc as s ~ N(s_o, alpha_distance s_o^2) and
// phi ~ N(phi_o, alpha_steering phi_o^2 + steering_floor) around the odometry's arc (s_o, phi_o),
// the physical inputs of a car; the same density, evaluated at the arcs of the trajectory's
// increments, is maximized here (as Thrun et al., Probabilistic Robotics, section 5.4, does for
// table 5.6's model).
#include <algorithm>
#include <cmath>
#include <string>

#include "calibrate_minimize.hpp"
#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/motion.hpp"

namespace mote::calibrate {
namespace {

constexpr double kAlphaMin = 1e-5;
constexpr double kAlphaMax = 2.0;
constexpr double kPoseVarMin = 1e-9;    // m^2, rad^2
constexpr double kPoseVarMax = 1e-3;    // as the diff fit: the refined poses' noise
constexpr double kExactPoseVar = 1e-8;  // a reference trajectory is taken as exact
constexpr std::size_t kMinSamples = 30;
constexpr int kEvaluations = 20000;
constexpr double kOutlier = 16.0;  // squared Mahalanobis distance: 4 sigma
// Odometry arcs steered beyond this share of full lock are left out: the motion's arc would
// reach the lock, where the model clamps it, within a few sigma of steering noise.
constexpr double kLockShare = 0.75;

// One increment as the arcs of the odometry and of the motion, with what the poses' noise adds.
struct ArcResidual {
  double s_odom = 0, phi_odom = 0;
  double ds = 0, dphi = 0;   // motion minus odometry
  double pose_along = 0;     // m^2, the poses' known position variance along the motion
  double pose_theta = 0;     // rad^2, both poses' known heading variance
  double phi_per_theta = 0;  // d phi / d dtheta at the motion: heading noise seen in phi
  double phi_per_s = 0;      // d phi / d s at the motion: position noise along it seen in phi
};

struct Params {
  double distance, steering, pose_xy, pose_theta;
};

Params params_from(const std::vector<double>& v, bool estimated) {
  return {v[0], v[1], estimated ? v[2] : kExactPoseVar, estimated ? v[3] : kExactPoseVar};
}

// -log of the two independent Gaussians up to the constant, and the larger squared
// Mahalanobis distance of the two (for the outlier cut). The poses' position noise along the
// motion also moves phi (through s); that correlation between the two residuals is left out.
double sample_nll(const ArcResidual& r, const Params& p, double floor, double* worst = nullptr) {
  const double along = r.pose_along + p.pose_xy;
  const double vs = p.distance * r.s_odom * r.s_odom + along;
  const double vphi = p.steering * r.phi_odom * r.phi_odom + floor +
                      r.phi_per_theta * r.phi_per_theta * (r.pose_theta + 2 * p.pose_theta) +
                      r.phi_per_s * r.phi_per_s * along;
  const double qs = r.ds * r.ds / vs;
  const double qphi = r.dphi * r.dphi / vphi;
  if (worst != nullptr) *worst = std::max(qs, qphi);
  return 0.5 * (qs + std::log(vs) + qphi + std::log(vphi));
}

double total_nll(const std::vector<ArcResidual>& rs, const Params& p, double floor) {
  double sum = 0;
  for (const ArcResidual& r : rs) sum += sample_nll(r, p, floor);
  return sum;
}

double project(const PoseCovariance& c, double x, double y) {
  return c.xx * x * x + 2 * c.xy * x * y + c.yy * y * y;
}

bool finite(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

// The arcs of one increment, or nothing when the odometry's has no steering angle to speak of:
// a step too short for its direction (a turn on the spot is no arc a car drives), one near full
// lock (where the model clamps the motion's arc, cutting its residual off), or one that is not
// finite. The choice looks at the odometry only: choosing on the motion's arc would cut off
// the very noise being fitted.
bool arc_residual(const MotionSample& m, const AckermannModel& model, double min_travel,
                  ArcResidual& r) {
  if (!finite(m.odometry) || !finite(m.motion)) return false;
  const AckermannArc o = ackermann_arc(m.odometry, model.wheelbase, model.max_steering);
  const AckermannArc t = ackermann_arc(m.motion, model.wheelbase, model.max_steering);
  if (std::abs(o.length) < min_travel || std::abs(o.steering) > kLockShare * model.max_steering ||
      t.length == 0.0) {
    return false;
  }
  r.s_odom = o.length;
  r.phi_odom = o.steering;
  r.ds = t.length - o.length;
  r.dphi = t.steering - o.steering;
  // The chord's direction, the mid-arc heading, in the map frame.
  const double heading = m.heading_before + 0.5 * m.motion.theta;
  const double ux = std::cos(heading), uy = std::sin(heading);
  r.pose_along = project(m.before, ux, uy) + project(m.after, ux, uy);
  r.pose_theta = m.before.tt + m.after.tt;
  // phi = atan(q), q = L dtheta / s: d phi / d dtheta = (L / s) / (1 + q^2) and
  // d phi / d s = -(q / s) / (1 + q^2) = -sin(2 phi) / (2 s).
  const double k = model.wheelbase / t.length;
  const double q = k * m.motion.theta;
  r.phi_per_theta = k / (1 + q * q);
  r.phi_per_s = -(q / t.length) / (1 + q * q);
  return true;
}

std::vector<detail::Bounded> bounds(bool estimated) {
  std::vector<detail::Bounded> b{{0.05, kAlphaMin, kAlphaMax}, {0.05, kAlphaMin, kAlphaMax}};
  if (estimated) {
    const double start = std::sqrt(kPoseVarMin * kPoseVarMax);
    b.push_back({start, kPoseVarMin, kPoseVarMax});
    b.push_back({start, kPoseVarMin, kPoseVarMax});
  }
  return b;
}

}  // namespace

AckermannFit fit_ackermann_noise(const std::vector<MotionSample>& samples, double wheelbase,
                                 bool estimated_poses) {
  AckermannModel model;
  model.wheelbase = wheelbase;
  // Between estimated poses a step shorter than a few times their position noise has no
  // direction, and its steering angle would be noise (as in the diff fit).
  const double min_travel = estimated_poses ? 0.05 : 0.01;
  std::vector<ArcResidual> rs;
  for (const MotionSample& m : samples) {
    ArcResidual r;
    if (arc_residual(m, model, min_travel, r)) rs.push_back(r);
  }
  const auto check_count = [&](const char* which) {
    if (rs.size() < kMinSamples) {
      throw Error("Ackermann fit: " + std::to_string(rs.size()) + " of " +
                  std::to_string(samples.size()) + " increments " + which + " (longer than " +
                  std::to_string(min_travel) + " m, steered below 3/4 of full lock), at least " +
                  std::to_string(kMinSamples) + " needed");
    }
  };
  check_count("are arcs a car drives");
  const double floor = model.steering_floor;
  const Params start{model.alpha_distance, model.alpha_steering, 1e-4, 1e-4};
  AckermannFit fit;
  int evals = 0;
  auto fit_once = [&] {
    return params_from(detail::minimize(
                           [&](const std::vector<double>& v) {
                             return total_nll(rs, params_from(v, estimated_poses), floor);
                           },
                           bounds(estimated_poses), kEvaluations, evals),
                       estimated_poses);
  };
  Params p = fit_once();
  fit.quality.iterations = evals;
  // Increments beyond 4 sigma of the first fit are poses the trajectory got wrong, not
  // odometry noise (as in the diff fit): left out and the fit repeated.
  // Arcs whose motion could reach full lock within 3 sigma of the first fit's steering noise
  // go too: the model clamps there, so their residual is cut off (the fixed 3/4 of the lock
  // above is only a first guess, too little for noisy steering).
  std::vector<ArcResidual> kept;
  std::size_t near_lock = 0;
  for (const ArcResidual& r : rs) {
    double worst = 0;
    sample_nll(r, p, floor, &worst);
    const double sd_phi = std::sqrt(p.steering * r.phi_odom * r.phi_odom + floor);
    if (std::abs(r.phi_odom) + 3 * sd_phi >= model.max_steering) {
      ++near_lock;
    } else if (worst < kOutlier) {
      kept.push_back(r);
    }
  }
  fit.outliers = rs.size() - kept.size() - near_lock;
  rs = std::move(kept);
  check_count("are arcs a car drives, within 4 sigma of a first fit and 3 sigma of the lock");
  p = fit_once();
  fit.quality.iterations += evals;
  fit.alpha_distance = p.distance;
  fit.alpha_steering = p.steering;
  fit.pose_variance_xy = estimated_poses ? p.pose_xy : 0.0;
  fit.pose_variance_theta = estimated_poses ? p.pose_theta : 0.0;
  fit.quality.samples = rs.size();
  fit.quality.log_likelihood_before = -total_nll(rs, start, floor);
  fit.quality.log_likelihood_after = -total_nll(rs, p, floor);
  if (p.distance <= kAlphaMin * 1.05) fit.quality.at_bound.push_back("alpha3 (lower bound 1e-05)");
  if (p.steering <= kAlphaMin * 1.05) fit.quality.at_bound.push_back("alpha1 (lower bound 1e-05)");
  if (p.distance >= kAlphaMax * 0.95) fit.quality.at_bound.push_back("alpha3 (upper bound 2)");
  if (p.steering >= kAlphaMax * 0.95) fit.quality.at_bound.push_back("alpha1 (upper bound 2)");
  return fit;
}

}  // namespace mote::calibrate
