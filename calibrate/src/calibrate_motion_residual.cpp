// One odometry increment against the motion it stood for, as the odometry fit reads it: the
// residuals in the motion's direction of travel and table 5.6's terms (amcl's conventions).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mote/calibrate/calibrate.hpp"

namespace mote::calibrate {
namespace {

// amcl's folding of a relative rotation (motion.cpp): driving backwards is a small rotation;
// fold_signed keeps its sign.
double fold_signed(double rot) {
  return std::abs(rot) > 0.5 * std::numbers::pi ? wrap_angle(rot - std::numbers::pi) : rot;
}
double fold(double rot) { return std::abs(fold_signed(rot)); }

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
  // The odometry's own split of its rotation, rot1 - rot2 (amcl's 1 cm rule, backward steps
  // folded): along_turns' regressor.
  const double rot1_odo = std::hypot(o.x, o.y) < 0.01 ? 0.0 : std::atan2(o.y, o.x);
  const double split = fold_signed(rot1_odo) - fold_signed(wrap_angle(o.theta - rot1_odo));
  r.split_odometry = split * split;
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

}  // namespace mote::calibrate
