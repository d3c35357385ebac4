// DIR/config.yaml of a calibration: flat amcl names (load_config reads it), every fitted value
// commented with what it was fitted from.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"

namespace mote::calibrate {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string quality(const FitQuality& q, const char* what) {
  std::string s = "# fitted from " + std::to_string(q.samples) + " " + what + ", log-likelihood " +
                  num(q.log_likelihood_before) + " (start) -> " + num(q.log_likelihood_after) +
                  " (fitted), " + std::to_string(q.iterations) + " iterations\n";
  for (const std::string& b : q.at_bound) s += "# AT BOUND: " + b + "\n";
  return s;
}

void sensor_section(std::ostringstream& y, const CalibrationResult& r, const CalibrationRound& f) {
  const LocalizerConfig& c = r.config;
  const BeamMixture& b = f.beam.params;
  if (c.laser_model_type == LaserModel::kBeam) {
    y << "# Beam model mixture by EM (Probabilistic Robotics, table 6.2, sec. 6.3.2), expected\n"
         "# ranges ray cast (Embree) at the poses.\n"
      << quality(f.beam.quality, "beams") << "laser_model_type: beam\n";
  } else {
    y << "# Likelihood field (table 6.3): z_hit, z_rand, sigma_hit by maximum likelihood of\n"
         "# z_hit N(d; 0, sigma_hit^2) + z_rand / z_max over endpoint distances d (EM).\n"
      << quality(f.field.quality, "beam endpoints") << "laser_model_type: likelihood_field\n";
  }
  y << "z_hit: " << num(c.z_hit) << "\n"
    << "z_rand: " << num(c.z_rand) << "\n";
  if (c.laser_model_type == LaserModel::kLikelihoodField) {
    y << "# The field's maximum-likelihood sigma_hit is " << num(f.field.params.sigma_hit)
      << " m; the config takes the larger of it and the range error's (beam fit, "
      << num(b.sigma_hit)
      << " m): the distance to the nearest wall understates the spread a\n"
         "# particle slightly off the pose meets (Intel: 0.025 m loses track, 0.07 m tracks).\n";
  }
  y << "sigma_hit: " << num(c.sigma_hit) << "  # m\n";
  if (c.laser_model_type == LaserModel::kLikelihoodField) {
    y << "# Beam model mixture by EM (table 6.2), for laser_model_type: beam (unused by the\n"
         "# likelihood field): z_hit "
      << num(b.z_hit) << ", sigma_hit " << num(b.sigma_hit) << " m, z_rand " << num(b.z_rand)
      << "\n"
      << quality(f.beam.quality, "beams");
  }
  y << "z_short: " << num(b.z_short) << "  # beam model, table 6.2\n"
    << "z_max: " << num(b.z_max) << "  # beam model, table 6.2\n"
    << "lambda_short: " << num(b.lambda_short) << "  # 1/m, beam model, table 6.2 (exact M-step)\n";
  const BeamCorrelation& k = f.correlation;
  y << "# Neighbouring beams' range errors are correlated (rho_1 "
    << num(k.rho.empty() ? 0.0 : k.rho.front()) << ", " << k.rho.size() << " lags summed, "
    << k.pairs
    << " pairs of hits): a scan\n# holds 1 / (1 + 2 sum rho_k) of its beams' "
       "information (sec. 6.3.4), the exponent below, used once the belief has settled\n"
       "# (global localization keeps the adaptive search).\n"
    << "tracking_tempering: " << num(c.tracking_tempering) << "\n";
  if (r.start.likelihood_tempering > 0.0) {
    y << "# The starting config's fixed likelihood_tempering (" << num(r.start.likelihood_tempering)
      << ") is dropped: tracking_tempering replaces the\n# adaptive search "
         "(likelihood_tempering: 0), which a fixed exponent leaves no room for.\n";
  }
}

void motion_section(std::ostringstream& y, const CalibrationResult& r, const CalibrationRound& f) {
  const LocalizerConfig& c = r.config;
  const OdometryFit& o = f.odometry;
  y << "\n# Odometry noise by maximum likelihood of the increments between updates (sec. 5.4,\n"
       "# table 5.6 lines 5-7: var rot1 = alpha1 rot1^2 + alpha2 trans^2, var trans = alpha3\n"
       "# trans^2 + alpha4 (rot1^2 + rot2^2)), zero-mean as the filter's model is.\n"
    << quality(o.quality, "increments")
    << "# Systematic part, which the filter's model lacks (so the alphas above cover it):\n"
    << "# translation scale error " << num(o.translation_bias) << ", rotation scale error "
    << num(o.rotation_bias) << "; without it the noise is alpha1 " << num(o.alphas.alpha1)
    << ", alpha2 " << num(o.alphas.alpha2) << ", alpha3 " << num(o.alphas.alpha3) << ", alpha4 "
    << num(o.alphas.alpha4) << ".\n"
    << "# Standard errors (observed information): alpha1 " << num(o.alphas_zero_mean_se.alpha1)
    << ", alpha2 " << num(o.alphas_zero_mean_se.alpha2) << ", alpha3 "
    << num(o.alphas_zero_mean_se.alpha3) << ", alpha4 " << num(o.alphas_zero_mean_se.alpha4)
    << "; scale errors " << num(o.translation_bias_se) << ", " << num(o.rotation_bias_se)
    << " (0: held at a bound); the alphas' are those of the zero-mean alphas below.\n"
    << "# " << o.outliers << " increments beyond 4 sigma of a first fit left out.\n"
    << "# Pose noise of the trajectory fitted alongside: " << num(o.pose_variance_xy) << " m^2, "
    << num(o.pose_variance_theta) << " rad^2.\n"
    << "odom_model_type: " << name_of(c.odom_model_type) << "\n";
  if (f.ackermann) {
    const AckermannFit& k = *f.ackermann;
    y << "# Ackermann (bicycle, wheelbase " << num(c.wheelbase)
      << " m), fitted on the arcs of the increments:\n"
         "# alpha1 is its steering noise (var phi = alpha1 phi^2 + 1e-4 rad^2), alpha3 its\n"
         "# distance noise (var s = alpha3 s^2); alpha2 and alpha4 are not read by this model.\n"
      << quality(k.quality, "arcs") << "# " << k.outliers
      << " arcs beyond 4 sigma of a first fit left out";
    if (!r.with_reference) {
      y << "; pose noise fitted alongside: " << num(k.pose_variance_xy) << " m^2, "
        << num(k.pose_variance_theta) << " rad^2";
    }
    y << ".\n";
  }
  y << "alpha1: " << num(c.alpha1) << "\n"
    << "alpha2: " << num(c.alpha2) << "\n"
    << "alpha3: " << num(c.alpha3) << "\n"
    << "alpha4: " << num(c.alpha4) << "\n"
    << "# omni model fit on the same increments: alpha1 " << num(o.alphas_omni.alpha1)
    << ", alpha2 " << num(o.alphas_omni.alpha2) << ", alpha3 " << num(o.alphas_omni.alpha3)
    << ", alpha4 " << num(o.alphas_omni.alpha4) << ", alpha5 " << num(o.alpha5) << "\n"
    << "alpha5: " << num(c.odom_model_type == OdomModel::kOmni ? c.alpha5 : o.alpha5) << "\n"
    << (c.adaptive_motion_noise
            ? "# The online estimate (odometry_noise.hpp) starts from the fit and keeps its margin "
              "over\n# it (Intel: the fitted alphas held fixed lose track, adapted from them the "
              "filter tracks).\n"
            : "# The online estimate (odometry_noise.hpp) is the differential model's only: this "
              "model\n# samples with the fitted alphas as they are.\n")
    << "adaptive_motion_noise: " << (c.adaptive_motion_noise ? "true" : "false") << "\n";
  if (r.margins.empty()) return;
  y << "# The online estimate's variance margin, chosen by how well the scans fit the map at the\n"
       "# filter's estimates (mean per-beam log-density over two tracking runs +- half their\n"
       "# difference, nats); a step is taken when it gains more than the two spreads:\n#";
  for (const MarginTrial& t : r.margins) {
    y << " " << num(t.margin) << ": " << num(t.fit) << " +- " << num(t.spread);
  }
  y << "\nmotion_noise_margin: " << num(c.motion_noise_margin) << "\n";
}

// What the fit does not set, as the starting config held it: the written file stands alone.
void unfitted_section(std::ostringstream& y, const CalibrationResult& r) {
  const LocalizerConfig defaults;
  LocalizerConfig rest = r.config;
  rest.laser_model_type = defaults.laser_model_type;
  rest.z_hit = defaults.z_hit;
  rest.z_rand = defaults.z_rand;
  rest.sigma_hit = defaults.sigma_hit;
  rest.z_short = defaults.z_short;
  rest.z_max = defaults.z_max;
  rest.lambda_short = defaults.lambda_short;
  rest.likelihood_tempering = defaults.likelihood_tempering;
  rest.tracking_tempering = defaults.tracking_tempering;
  rest.odom_model_type = defaults.odom_model_type;
  rest.alpha1 = defaults.alpha1;
  rest.alpha2 = defaults.alpha2;
  rest.alpha3 = defaults.alpha3;
  rest.alpha4 = defaults.alpha4;
  rest.alpha5 = defaults.alpha5;
  rest.adaptive_motion_noise = defaults.adaptive_motion_noise;
  rest.threads = defaults.threads;  // the calibrating machine's, not the filter's
  if (!r.margins.empty()) rest.motion_noise_margin = defaults.motion_noise_margin;
  const std::string kept = config_yaml(rest, defaults);
  if (kept.empty()) return;
  y << "\n# Not fitted: the starting config's (--config) other values that differ from mote's\n"
       "# defaults, so that this file alone reproduces the calibrated filter.\n"
    << kept;
}

}  // namespace

std::string calibration_yaml(const CalibrationResult& r) {
  const CalibrationRound& f = r.rounds.back();
  std::ostringstream y;
  y << "# mote calibrate: " << r.scans << " scans, " << f.poses << " poses used, "
    << (r.with_reference ? "poses from the reference trajectory"
                         : "poses from the filter's own trajectory")
    << ".\n";
  if (!r.with_reference) {
    y << "# Self-calibration: " << r.rounds.size() << " rounds of localize -> fit; "
      << (r.settled ? "settled: the last round moved no parameter by more than "
                    : "stopped at the round limit: the last round still moved a parameter by ")
      << num(f.largest_change)
      << (f.largest_change_of.empty() ? "" : " (" + f.largest_change_of + ")") << ".\n";
  }
  if (r.comparison) {
    y << "# Replayed with both on this log: " << (fitted_is_better(*r.comparison) ? "" : "NOT ")
      << "better than " << r.comparison->start_name << " (comparison.yaml).\n";
  }
  y << "# Load with mote replay --config or mote::load_config.\n\n";
  sensor_section(y, r, f);
  motion_section(y, r, f);
  unfitted_section(y, r);
  return y.str();
}

std::filesystem::path write_calibration(const CalibrationResult& result,
                                        const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error("cannot create directory '" + directory.string() + "': " + ec.message());
  const std::filesystem::path yaml = directory / "config.yaml";
  std::ofstream out(yaml);
  out << calibration_yaml(result);
  if (!out) throw Error("cannot write '" + yaml.string() + "'");
  out.close();
  write_calibration_png(result, directory / "calibration.png");
  if (result.comparison) {
    const std::filesystem::path path = directory / "comparison.yaml";
    std::ofstream c(path);
    c << comparison_yaml(*result.comparison);
    if (!c) throw Error("cannot write '" + path.string() + "'");
  }
  return yaml;
}

}  // namespace mote::calibrate
