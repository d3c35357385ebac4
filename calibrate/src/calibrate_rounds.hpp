#pragma once
/// \file
/// One calibration round against the one before it, and the config a round's fits make.

#include <vector>

#include "mote/calibrate/calibrate.hpp"
#include "mote/engine/localizer_config.hpp"

namespace mote::calibrate::detail {

/// Sets r.largest_change and r.largest_change_of: the figure of r that moved most from `prev`
/// (relative for scales, absolute for weights; the odometry noise as the mean change of the
/// standard deviations it predicts over `increments`).
void measure_change(CalibrationRound& r, const CalibrationRound& prev,
                    const std::vector<MotionResidual>& increments);

/// `c` with round r's fits applied (sensor mixture, tempering, odometry noise).
[[nodiscard]] LocalizerConfig apply_fit(LocalizerConfig c, const CalibrationRound& r);

}  // namespace mote::calibrate::detail
