// `mote calibrate`: the sensor and motion model parameters fitted from a recorded log.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <iostream>
#include <string>

#include "args.hpp"
#include "calibrate_compare.hpp"
#include "commands.hpp"
#include "mote/calibrate/calibrate.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/replay/report.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 11> kFlags{{
    {"map", "MAP.yaml", "map_server map (required)"},
    {"log", "LOG", "recorded log (CARMEN, ROS 1 bag, ROS 2), as mote replay reads it (required)"},
    {"out", "DIR",
     "output folder for config.yaml and calibration.png, created if missing (required)"},
    {"reference", "REF.tum",
     "reference poses (TUM): fit against them once; without, localize -> fit rounds"},
    {"config", "CONFIG.yaml", "starting LocalizerConfig; fitted values replace its fields"},
    {"model", "NAME",
     "laser model the config is for: likelihood_field or beam (default likelihood_field)"},
    {"rounds", "N", "self-calibration rounds at most (default 6)"},
    {"beams", "N", "beams per scan the sensor fits use (default 90)"},
    {"threads", "N", "worker threads, 0 = every core (default 0)"},
    {"particles", "N",
     "particles (min = max) of the tracking runs that choose motion_noise_margin; default: the "
     "config's KLD bounds. Pass the count you will run"},
    {"laser-max-range", "M", "m, the no-return reading of CARMEN FLASER logs (default: inferred)"},
}};

constexpr std::string_view kUsage =
    "mote calibrate --map MAP.yaml --log LOG --out DIR [--reference REF.tum] [flags]";
constexpr std::string_view kAbout =
    "Fits the beam mixture (EM, Probabilistic Robotics table 6.2), the likelihood field's\n"
    "z_hit/z_rand/sigma_hit (maximum likelihood) and the odometry alphas (maximum likelihood,\n"
    "section 5.4) and writes DIR/config.yaml (for mote replay --config) and DIR/calibration.png.\n"
    "Without --reference the filter's own trajectory is the reference: localize, fit, localize\n"
    "again with the fit, until no parameter moves by more than 10% (at most 6 rounds). Then\n"
    "chooses the online odometry noise's margin (motion_noise_margin) by tracking runs scored by\n"
    "how well the scans fit the map at the estimates. Last, replays the log with the fitted\n"
    "config and with the starting one (same seed and particles) and says which tracked better:\n"
    "by the ATE with --reference, else by the scans' fit (DIR/comparison.yaml). Keep the\n"
    "starting config when the verdict says the fit is NOT better.";

calibrate::CalibrationProgress progress_bar() {
  if (isatty(STDERR_FILENO) == 0) return {};
  return [](int run, std::size_t done, std::size_t total) {
    if (done % 20 != 0 && done != total) return;
    constexpr std::size_t kWidth = 40;
    const std::size_t filled = total == 0 ? 0 : done * kWidth / total;
    std::fprintf(stderr, "\rfilter run %d [%s%s] %zu/%zu scans", run + 1,
                 std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(), done,
                 total);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  };
}

calibrate::CalibrationOptions options_from(const ParsedArgs& args) {
  calibrate::CalibrationOptions o;
  o.map = args.required("map");
  o.log = args.required("log");
  if (auto r = args.text("reference")) o.reference = *r;
  if (auto path = args.text("config")) {
    LoadedConfig loaded = load_config(*path);
    for (const std::string& w : loaded.warnings)
      std::cerr << "mote calibrate: warning: " << w << '\n';
    o.config = loaded.config;
  }
  if (auto m = args.text("model")) {
    if (*m == "beam") {
      o.config.laser_model_type = LaserModel::kBeam;
    } else if (*m == "likelihood_field") {
      o.config.laser_model_type = LaserModel::kLikelihoodField;
    } else {
      throw args.error("model", "expects likelihood_field or beam, got '" + *m + "'");
    }
  }
  if (auto n = args.integer("rounds", 1, 50)) o.max_rounds = static_cast<int>(*n);
  if (auto n = args.integer("beams", 1, 100'000)) o.beams_per_scan = static_cast<int>(*n);
  if (auto n = args.integer("threads", 0, 4096)) o.config.threads = static_cast<int>(*n);
  if (auto n = args.integer("particles", 1, 100'000'000)) o.particles = static_cast<int>(*n);
  if (auto m = args.real("laser-max-range", 0.01, 1e6)) {
    o.reader.carmen_max_range = static_cast<float>(*m);
    o.config.laser_max_range = *m;
  }
  o.progress = progress_bar();
  return o;
}

void print_summary(const calibrate::CalibrationResult& r, const std::filesystem::path& yaml) {
  const calibrate::CalibrationRound& f = r.rounds.back();
  std::printf("calibrated from %zu scans (%zu poses, %s) in %.1f s\n", r.scans, f.poses,
              r.with_reference ? "reference" : "filter's own trajectory", r.wall_s);
  if (!r.with_reference) {
    std::printf("  rounds        %zu (%s; last change %.3g in %s)\n", r.rounds.size(),
                r.settled ? "settled" : "round limit", f.largest_change,
                f.largest_change_of.c_str());
  }
  for (std::size_t k = 0; k < r.rounds.size() && !r.with_reference; ++k) {
    const calibrate::CalibrationRound& q = r.rounds[k];
    const OdometryAlphas& a = q.odometry.alphas_zero_mean;
    std::printf(
        "  round %zu       %zu poses: sigma_hit %.4f m (beam %.4f m), tempering %.3f, alphas %.4g "
        "%.4g %.4g %.4g\n",
        k + 1, q.poses, q.field.params.sigma_hit, q.beam.params.sigma_hit, q.correlation.tempering,
        a.alpha1, a.alpha2, a.alpha3, a.alpha4);
  }
  const calibrate::FieldMixture& lf = f.field.params;
  const calibrate::BeamMixture& b = f.beam.params;
  const OdometryAlphas& a = f.odometry.alphas_zero_mean;
  std::printf("  field         z_hit %.3f  z_rand %.3f  sigma_hit %.4f m\n", lf.z_hit, lf.z_rand,
              lf.sigma_hit);
  std::printf(
      "  beam          z_hit %.3f  z_short %.3f  z_max %.3f  z_rand %.3f  sigma_hit %.4f m  "
      "lambda_short %.3f\n",
      b.z_hit, b.z_short, b.z_max, b.z_rand, b.sigma_hit, b.lambda_short);
  const calibrate::BeamCorrelation& c = f.correlation;
  std::printf(
      "  tempering     %.3f (neighbouring beams' range errors: rho_1 %.3f, %zu lags, %zu "
      "pairs)\n",
      c.tempering, c.rho.empty() ? 0.0 : c.rho.front(), c.rho.size(), c.pairs);
  const OdometryAlphas& se = f.odometry.alphas_zero_mean_se;
  std::printf(
      "  odometry      alpha1 %.4g+-%.2g  alpha2 %.4g+-%.2g  alpha3 %.4g+-%.2g  alpha4 %.4g+-%.2g "
      "(bias: trans %.3f+-%.3f, rot %.3f+-%.3f; +- one standard error)\n",
      a.alpha1, se.alpha1, a.alpha2, se.alpha2, a.alpha3, se.alpha3, a.alpha4, se.alpha4,
      f.odometry.translation_bias, f.odometry.translation_bias_se, f.odometry.rotation_bias,
      f.odometry.rotation_bias_se);
  if (!r.margins.empty()) {
    std::printf("  noise margin  %.3g (scan fit at the estimates, nats:",
                r.config.motion_noise_margin);
    for (const calibrate::MarginTrial& t : r.margins) {
      std::printf(" %.3g: %.4f+-%.4f", t.margin, t.fit, t.spread);
    }
    std::printf(")\n");
  }
  if (f.ackermann) {
    std::printf("  ackermann     alpha1 (steering) %.4g  alpha3 (distance) %.4g, %zu arcs\n",
                f.ackermann->alpha_steering, f.ackermann->alpha_distance,
                f.ackermann->quality.samples);
  }
  std::printf("  config        %s\n", yaml.string().c_str());
}

// One line per fitted group saying whether it settled, and one per parameter on a bound.
void print_verdicts(const calibrate::CalibrationResult& r, const calibrate::CalibrationOptions& o) {
  using Status = calibrate::GroupVerdict::Status;
  for (const calibrate::GroupVerdict& v : calibrate::judge_calibration(r, o.settle)) {
    const double pct = 100.0 * v.last_change;
    const char* name = v.group.c_str();
    const char* of = v.last_change_of.c_str();
    switch (v.status) {
      case Status::kFitOnce:
        std::printf("%s: fitted once against the reference poses (no rounds)\n", name);
        break;
      case Status::kConverged:
        std::printf("%s: converged in %zu rounds (last change %.1f %% in %s, below %.0f %%)\n",
                    name, v.rounds, pct, of, 100.0 * o.settle);
        break;
      case Status::kWithinSpread:
        std::printf(
            "%s: settled within its statistical spread in %zu rounds (last change %.1f %%, every "
            "alpha within 2 standard errors of the previous round's)\n",
            name, v.rounds, pct);
        break;
      case Status::kNotConverged:
        if (v.rounds < 2) {
          std::printf("%s: NOT converged: one round, no change to judge (rerun with --rounds 3)\n",
                      name);
        } else {
          std::printf(
              "%s: NOT converged: round limit, last change %.1f %% in %s (rerun with "
              "--rounds %zu)\n",
              name, pct, of, v.rounds + 3);
        }
        break;
    }
    for (const std::string& b : v.at_bound)
      std::printf("%s: parameter at its bound: %s\n", name, b.c_str());
  }
}

}  // namespace

int calibrate_command(std::span<char* const> words) {
  const ParsedArgs args = parse_args("calibrate", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  const std::filesystem::path out = args.required("out");
  const calibrate::CalibrationOptions options = options_from(args);
  replay::make_output_folder(out);  // before the rounds of replays, not after them
  calibrate::CalibrationResult result = calibrate::calibrate(options);
  const auto start = args.text("config");
  std::cerr << "mote calibrate: replaying the log with the fitted config and with "
            << (start ? *start : "mote's defaults") << " to compare them\n";
  result.comparison = compare_with_start(options, result, start ? *start : "mote's defaults");
  const std::filesystem::path yaml = calibrate::write_calibration(result, out);
  print_summary(result, yaml);
  print_verdicts(result, options);
  std::printf("verdict: %s\n",
              calibrate::comparison_verdict(*result.comparison, yaml.string()).c_str());
  return 0;
}

}  // namespace mote::tool
