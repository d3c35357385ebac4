// The fitted config against the starting one on the calibration's own log: which did better,
// in the verdict's words and in DIR/comparison.yaml (docs/calibration.md, "The verdict").
#include <cmath>
#include <cstdio>
#include <string>

#include "mote/calibrate/calibrate.hpp"

namespace mote::calibrate {
namespace {

bool lower_is_better(const StartComparison& c) { return c.metric == "ate_rmse_m"; }

std::string num(const char* format, double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// "ATE 0.0371 m against 0.0314 m (5000 particles, seed 42)", or without a reference "scan fit
// at the estimates 1.7073 against 1.7764 nats per beam (no reference, higher is better; ...)".
std::string figures(const StartComparison& c) {
  std::string s;
  if (lower_is_better(c)) {
    s.append("ATE ").append(num("%.4f", c.fitted)).append(" m against ");
    s.append(num("%.4f", c.start)).append(" m (");
  } else {
    s.append("scan fit at the estimates ").append(num("%.4f", c.fitted)).append(" against ");
    s.append(num("%.4f", c.start)).append(" nats per beam (no reference, higher is better; ");
  }
  s.append(std::to_string(c.min_particles));
  if (c.max_particles != c.min_particles) s.append("-").append(std::to_string(c.max_particles));
  return s.append(" particles, seed ").append(std::to_string(c.seed)).append(")");
}

}  // namespace

bool fitted_is_better(const StartComparison& c) {
  if (!std::isfinite(c.fitted)) return false;
  if (!std::isfinite(c.start)) return true;
  return lower_is_better(c) ? c.fitted < c.start : c.fitted > c.start;
}

std::string comparison_verdict(const StartComparison& c, const std::string& fitted_config) {
  const bool from_file = c.start_name != "mote's defaults";
  std::string s = "replayed with both on this log, the fitted config is ";
  if (fitted_is_better(c)) {
    s.append("better than ").append(c.start_name).append(": ").append(figures(c));
    s.append("; run with --config ").append(fitted_config);
    return s;
  }
  s.append("NOT better than ").append(c.start_name).append(": ").append(figures(c));
  s.append("; keep ").append(c.start_name);
  if (from_file) return s.append(" (run with --config ").append(c.start_name).append(")");
  return s.append(" (run without --config)");
}

std::string comparison_yaml(const StartComparison& c) {
  std::string y =
      "# mote calibrate: the log replayed with the fitted config and with the starting one\n"
      "# (same seed, particles and start); config.yaml is worth using only when `better` is\n"
      "# fitted.\n";
  y.append("metric: ")
      .append(c.metric)
      .append(lower_is_better(c) ? "  # m, lower is better\n"
                                 : "  # nats per beam, higher is better\n");
  y.append("fitted: ").append(num("%.6g", c.fitted)).append("\n");
  y.append("start: ").append(num("%.6g", c.start)).append("\n");
  y.append("start_config: \"").append(c.start_name).append("\"\n");
  y.append("better: ").append(fitted_is_better(c) ? "fitted" : "start").append("\n");
  y.append("min_particles: ").append(std::to_string(c.min_particles)).append("\n");
  y.append("max_particles: ").append(std::to_string(c.max_particles)).append("\n");
  y.append("seed: ").append(std::to_string(c.seed)).append("\n");
  y.append("updates_fitted: ").append(std::to_string(c.updates)).append("\n");
  y.append("updates_start: ").append(std::to_string(c.start_updates)).append("\n");
  return y;
}

}  // namespace mote::calibrate
