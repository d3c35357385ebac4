#pragma once
// `mote calibrate`'s last step: the fitted config against the starting one, each replayed on
// the calibration's own log.

#include <string>

#include "mote/calibrate/calibrate.hpp"

namespace mote::tool {

/// Replays options.log twice, with the config `mote replay --config DIR/config.yaml` loads
/// (calibration_yaml(result), parsed) and with options.config (`start_name`: "mote's defaults"
/// or its file), at the same seed, particle counts (options.particles when set) and start
/// (the reference's first pose with options.reference, else global), and compares the ATE
/// against options.reference, or without one calibrate::scan_fit (StartComparison).
[[nodiscard]] calibrate::StartComparison compare_with_start(
    const calibrate::CalibrationOptions& options, const calibrate::CalibrationResult& result,
    const std::string& start_name);

}  // namespace mote::tool
