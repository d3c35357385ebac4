// What changes from one calibration round to the next: how far the fitted figures moved (the
// loop stops when they settle) and the config a round's fits make.
#include "calibrate_rounds.hpp"

#include <algorithm>
#include <cmath>

namespace mote::calibrate::detail {
namespace {

// How far the noise the alphas predict moved: the mean, over the round's increments, of the
// larger relative change of the predicted standard deviations of the heading (rot1 + rot2:
// alpha1 (rot1^2 + rot2^2) + 2 alpha2 trans^2) and of the translation (alpha3 trans^2 + alpha4
// (rot1^2 + rot2^2); table 5.6, lines 5-7, as odometry_noise.hpp reads them). Not alpha by
// alpha: where a log's turns come with translation, alpha1 and alpha2 (alpha3 and alpha4) trade
// off (Intel: alpha1 jumps between 1e-5 and 0.0055 from one round to the next while alpha2
// takes up the difference).
double noise_change(const OdometryAlphas& a, const OdometryAlphas& b,
                    const std::vector<MotionResidual>& increments) {
  const auto sd_change = [](double now, double before) {
    return before > 0.0 ? std::abs(std::sqrt(now / before) - 1.0) : 0.0;
  };
  double sum = 0.0;
  for (const MotionResidual& m : increments) {
    const double turns = m.rot1 * m.rot1 + m.rot2 * m.rot2, trans = m.trans * m.trans;
    const double heading = sd_change(a.alpha1 * turns + 2.0 * a.alpha2 * trans,
                                     b.alpha1 * turns + 2.0 * b.alpha2 * trans);
    const double along =
        sd_change(a.alpha3 * trans + a.alpha4 * turns, b.alpha3 * trans + b.alpha4 * turns);
    sum += std::max(heading, along);
  }
  return increments.empty() ? 0.0 : sum / static_cast<double>(increments.size());
}

enum class Group { kSensor, kMotion };

void note_change(double change, const char* name, CalibrationRound& r, Group group) {
  if (change > r.largest_change) {
    r.largest_change = change;
    r.largest_change_of = name;
  }
  double& of_group = group == Group::kSensor ? r.sensor_change : r.motion_change;
  std::string& name_of_group = group == Group::kSensor ? r.sensor_change_of : r.motion_change_of;
  if (change > of_group) {
    of_group = change;
    name_of_group = name;
  }
}

// Relative change of a scale parameter, absolute change of a weight. Ackermann's alphas below
// 1e-3 count as 1e-3: a term that small is no noise worth the name, and one near its lower
// bound (1e-5) would otherwise "change" by a factor of five between rounds.
void compare(double a, double b, bool weight, const char* name, CalibrationRound& r, Group group) {
  note_change(weight ? std::abs(a - b) : std::abs(a - b) / std::max(std::abs(b), 1e-3), name, r,
              group);
}

}  // namespace

void measure_change(CalibrationRound& r, const CalibrationRound& prev,
                    const std::vector<MotionResidual>& increments) {
  const Group sensor = Group::kSensor, motion = Group::kMotion;
  compare(r.field.params.sigma_hit, prev.field.params.sigma_hit, false, "sigma_hit", r, sensor);
  compare(r.field.params.z_hit, prev.field.params.z_hit, true, "z_hit", r, sensor);
  compare(r.beam.params.sigma_hit, prev.beam.params.sigma_hit, false, "beam sigma_hit", r, sensor);
  compare(r.beam.params.z_hit, prev.beam.params.z_hit, true, "beam z_hit", r, sensor);
  compare(r.correlation.tempering, prev.correlation.tempering, false, "tracking_tempering", r,
          sensor);
  note_change(noise_change(r.odometry.alphas_zero_mean, prev.odometry.alphas_zero_mean, increments),
              "odometry noise (alpha1-alpha4)", r, motion);
  if (r.ackermann && prev.ackermann) {
    compare(r.ackermann->alpha_steering, prev.ackermann->alpha_steering, false, "Ackermann alpha1",
            r, motion);
    compare(r.ackermann->alpha_distance, prev.ackermann->alpha_distance, false, "Ackermann alpha3",
            r, motion);
  }
}

LocalizerConfig apply_fit(LocalizerConfig c, const CalibrationRound& r) {
  const BeamMixture& b = r.beam.params;
  c.z_short = b.z_short;
  c.z_max = b.z_max;
  c.lambda_short = b.lambda_short;
  if (c.laser_model_type == LaserModel::kBeam) {
    c.z_hit = b.z_hit;
    c.z_rand = b.z_rand;
    c.sigma_hit = b.sigma_hit;
  } else {
    c.z_hit = r.field.params.z_hit;
    c.z_rand = r.field.params.z_rand;
    // The endpoint's distance to the nearest wall is at most its range error, so the field's
    // own sigma understates the spread a particle a little off the pose meets; the range error
    // (the beam fit) bounds it from above. Measured on Intel (5000 particles): the field's
    // sigma 0.025 m loses track (ATE 1.9 m), the range error's 0.07 m tracks (0.056 m).
    c.sigma_hit = std::max(r.field.params.sigma_hit, b.sigma_hit);
  }
  c.tracking_tempering = r.correlation.tempering;
  c.likelihood_tempering =
      0.0;  // the adaptive search, which tracking_tempering replaces once settled
  const OdometryAlphas& a =
      c.odom_model_type == OdomModel::kOmni ? r.odometry.alphas_omni : r.odometry.alphas_zero_mean;
  c.alpha1 = a.alpha1;
  c.alpha2 = a.alpha2;
  c.alpha3 = a.alpha3;
  c.alpha4 = a.alpha4;
  if (c.odom_model_type == OdomModel::kOmni) c.alpha5 = r.odometry.alpha5;
  if (r.ackermann) {  // AckermannModel reads alpha3 as its distance noise, alpha1 as steering
    c.alpha1 = r.ackermann->alpha_steering;
    c.alpha3 = r.ackermann->alpha_distance;
  }
  // The fit starts the online estimate (odometry_noise.hpp), which keeps its margin over the
  // noise: on Intel the fitted alphas held fixed lose track (ATE 2.3 m), adapted from them the
  // filter tracks (0.056 m); the diff model only (the online fit is diff-only).
  c.adaptive_motion_noise = c.odom_model_type == OdomModel::kDiff;
  return c;
}

}  // namespace mote::calibrate::detail
