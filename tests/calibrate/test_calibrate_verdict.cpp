// judge_calibration: a group converges below the settle threshold, the odometry also when its
// alphas moved within their standard errors, and parameters on a bound are named.
#include <gtest/gtest.h>

#include "mote/calibrate/calibrate.hpp"

namespace mote::calibrate {
namespace {

using Status = GroupVerdict::Status;

CalibrationRound round_with(double sensor_change, double motion_change, double alpha1,
                            double alpha1_se) {
  CalibrationRound r;
  r.sensor_change = sensor_change;
  r.sensor_change_of = "sigma_hit";
  r.motion_change = motion_change;
  r.motion_change_of = "odometry noise (alpha1-alpha4)";
  r.odometry.alphas_zero_mean = {alpha1, 0.01, 0.01, 0.01};
  r.odometry.alphas_zero_mean_se = {alpha1_se, 0.001, 0.001, 0.001};
  return r;
}

CalibrationResult self_calibration(std::vector<CalibrationRound> rounds) {
  CalibrationResult r;
  r.rounds = std::move(rounds);
  return r;
}

TEST(CalibrationVerdict, BelowTheThresholdConverges) {
  const auto v = judge_calibration(
      self_calibration({round_with(0, 0, 0.01, 0.001), round_with(0.002, 0.05, 0.01, 0.001)}), 0.1);
  ASSERT_EQ(v.size(), 2U);
  EXPECT_EQ(v[0].group, "sensor");
  EXPECT_EQ(v[0].status, Status::kConverged);
  EXPECT_DOUBLE_EQ(v[0].last_change, 0.002);
  EXPECT_EQ(v[1].group, "odometry");
  EXPECT_EQ(v[1].status, Status::kConverged);
  EXPECT_EQ(v[1].rounds, 2U);
}

TEST(CalibrationVerdict, OdometryMovingWithinItsStandardErrorsHasSettled) {
  // alpha1 0.010 -> 0.013 with standard errors 0.001 each: 3e-3 > 2 * 1.41e-3, not settled.
  const auto moving = judge_calibration(
      self_calibration({round_with(0, 0, 0.010, 0.001), round_with(0.3, 0.43, 0.013, 0.001)}), 0.1);
  EXPECT_EQ(moving[0].status, Status::kNotConverged);  // the sensor has no spread test
  EXPECT_EQ(moving[1].status, Status::kNotConverged);
  EXPECT_EQ(moving[1].last_change_of, "odometry noise (alpha1-alpha4)");
  // The same move with standard errors of 0.002: within 2 * 2.8e-3.
  const auto spread = judge_calibration(
      self_calibration({round_with(0, 0, 0.010, 0.002), round_with(0.3, 0.43, 0.013, 0.002)}), 0.1);
  EXPECT_EQ(spread[1].status, Status::kWithinSpread);
}

TEST(CalibrationVerdict, OneRoundIsNotConvergedAndAReferenceFitIsFitOnce) {
  EXPECT_EQ(judge_calibration(self_calibration({round_with(0, 0, 0.01, 0.001)}), 0.1)[0].status,
            Status::kNotConverged);
  CalibrationResult with = self_calibration({round_with(0, 0, 0.01, 0.001)});
  with.with_reference = true;
  EXPECT_EQ(judge_calibration(with, 0.1)[1].status, Status::kFitOnce);
  EXPECT_TRUE(judge_calibration(CalibrationResult{}, 0.1).empty());
}

TEST(CalibrationVerdict, ParametersOnABoundAreNamedInTheirGroup) {
  CalibrationRound last = round_with(0.01, 0.01, 0.01, 0.001);
  last.field.quality.at_bound = {"z_rand (upper bound 0.5)"};
  last.odometry.quality.at_bound = {"alpha1 (lower bound 1e-05)"};
  const auto v = judge_calibration(self_calibration({round_with(0, 0, 0.01, 0.001), last}), 0.1);
  EXPECT_EQ(v[0].at_bound, std::vector<std::string>{"z_rand (upper bound 0.5)"});
  EXPECT_EQ(v[1].at_bound, std::vector<std::string>{"alpha1 (lower bound 1e-05)"});
}

}  // namespace
}  // namespace mote::calibrate
