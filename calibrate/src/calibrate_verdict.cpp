// judge_calibration: whether the sensor and the motion model's fits settled over the rounds
// (docs/calibration.md, "The verdict").
#include <cmath>

#include "mote/calibrate/calibrate.hpp"

namespace mote::calibrate {
namespace {

using Status = GroupVerdict::Status;

// Whether every alpha of the last two rounds' odometry fits differs by at most two standard
// errors of the difference: a change the log's increments cannot resolve, which more rounds do
// not reduce.
bool alphas_within_spread(const OdometryFit& a, const OdometryFit& b) {
  const OdometryAlphas& x = a.alphas_zero_mean;
  const OdometryAlphas& y = b.alphas_zero_mean;
  const OdometryAlphas& sx = a.alphas_zero_mean_se;
  const OdometryAlphas& sy = b.alphas_zero_mean_se;
  const auto within = [](double u, double v, double su, double sv) {
    return std::abs(u - v) <= 2.0 * std::hypot(su, sv);
  };
  return within(x.alpha1, y.alpha1, sx.alpha1, sy.alpha1) &&
         within(x.alpha2, y.alpha2, sx.alpha2, sy.alpha2) &&
         within(x.alpha3, y.alpha3, sx.alpha3, sy.alpha3) &&
         within(x.alpha4, y.alpha4, sx.alpha4, sy.alpha4);
}

Status status_of(const CalibrationResult& r, double change, double settle, bool spread_test) {
  if (r.with_reference || r.rounds.size() < 2) {
    return r.with_reference ? Status::kFitOnce : Status::kNotConverged;
  }
  if (change < settle) return Status::kConverged;
  const CalibrationRound& last = r.rounds.back();
  const CalibrationRound& before = r.rounds[r.rounds.size() - 2];
  if (spread_test && alphas_within_spread(last.odometry, before.odometry)) {
    return Status::kWithinSpread;
  }
  return Status::kNotConverged;
}

std::vector<std::string> joined(std::initializer_list<const FitQuality*> fits) {
  std::vector<std::string> out;
  for (const FitQuality* q : fits) out.insert(out.end(), q->at_bound.begin(), q->at_bound.end());
  return out;
}

}  // namespace

std::vector<GroupVerdict> judge_calibration(const CalibrationResult& r, double settle) {
  if (r.rounds.empty()) return {};
  const CalibrationRound& last = r.rounds.back();
  GroupVerdict sensor{"sensor",
                      status_of(r, last.sensor_change, settle, false),
                      r.rounds.size(),
                      last.sensor_change,
                      last.sensor_change_of,
                      joined({&last.field.quality, &last.beam.quality})};
  const bool ackermann = last.ackermann.has_value();
  GroupVerdict motion{"odometry",
                      status_of(r, last.motion_change, settle, !ackermann),
                      r.rounds.size(),
                      last.motion_change,
                      last.motion_change_of,
                      ackermann ? joined({&last.odometry.quality, &last.ackermann->quality})
                                : joined({&last.odometry.quality})};
  return {sensor, motion};
}

}  // namespace mote::calibrate
