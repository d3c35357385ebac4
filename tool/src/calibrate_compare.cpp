// The fitted config against the starting one on the calibration's log: two replays that
// differ in the config alone.
#include "calibrate_compare.hpp"

#include <cmath>
#include <limits>

#include "mote/engine/localizer_config.hpp"
#include "mote/replay/replay_run.hpp"

namespace mote::tool {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The run's ATE against the reference, or without one how well the scans fit the map along
// its trajectory (calibrate::scan_fit).
double score(const calibrate::CalibrationOptions& o, const calibrate::CalibrationResult& result,
             const replay::ReplayResult& r) {
  if (!o.reference.empty()) return r.errors && r.errors->matched > 0 ? r.errors->ate_rmse_m : kNaN;
  return r.trajectory.empty() ? kNaN : calibrate::scan_fit(o, result, r.trajectory);
}

}  // namespace

calibrate::StartComparison compare_with_start(const calibrate::CalibrationOptions& options,
                                              const calibrate::CalibrationResult& result,
                                              const std::string& start_name) {
  LocalizerConfig start = options.config;
  if (options.particles > 0) start.min_particles = start.max_particles = options.particles;
  // What the written file gives `mote replay --config`, not result.config: the file rounds.
  LocalizerConfig fitted = parse_config(calibrate::calibration_yaml(result), "config.yaml").config;
  fitted.min_particles = start.min_particles;
  fitted.max_particles = start.max_particles;
  fitted.seed = start.seed;
  fitted.threads = start.threads;

  replay::ReplayOptions run;
  run.map = options.map;
  run.log = options.log;
  run.reference = options.reference;
  run.reader = options.reader;
  const bool with_reference = !options.reference.empty();

  calibrate::StartComparison c;
  c.metric = with_reference ? "ate_rmse_m" : "scan_fit";
  c.start_name = start_name;
  c.min_particles = start.min_particles;
  c.max_particles = start.max_particles;
  c.seed = start.seed;
  run.config = fitted;
  const replay::ReplayResult with_fit = replay::run_replay(run);
  c.fitted = score(options, result, with_fit);
  c.updates = with_fit.updates.size();
  run.config = start;
  const replay::ReplayResult with_start = replay::run_replay(run);
  c.start = score(options, result, with_start);
  c.start_updates = with_start.updates.size();
  return c;
}

}  // namespace mote::tool
