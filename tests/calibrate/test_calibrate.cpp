// mote calibrate: the fits recover known parameters, on draws and on simulated logs whose noise
// the simulator drew from the models themselves (its --alphas / --mixture knobs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"
#include "mote/logs/carmen_writer.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/sim/simulate.hpp"
#include "mote_test/log_files.hpp"

namespace mote::calibrate {
namespace {

// --- the fits on draws ---------------------------------------------------------------------

TEST(CalibrateFits, BeamMixtureRecoversTable61Mixture) {
  const BeamMixture truth{.z_hit = 0.7,
                          .z_short = 0.15,
                          .z_max = 0.05,
                          .z_rand = 0.1,
                          .sigma_hit = 0.08,
                          .lambda_short = 0.7};
  constexpr double kMax = 20.0;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0), wall(1.0, 12.0);
  std::normal_distribution<double> n(0.0, truth.sigma_hit);
  std::vector<BeamSample> samples;
  for (int i = 0; i < 40000; ++i) {
    const double zs = wall(rng);
    const double pick = u(rng);
    double z = kMax;
    if (pick < truth.z_hit) {
      z = zs + n(rng);
    } else if (pick < truth.z_hit + truth.z_short) {
      z = -std::log1p(u(rng) * std::expm1(-truth.lambda_short * zs)) / truth.lambda_short;
    } else if (pick > truth.z_hit + truth.z_short + truth.z_max) {
      z = u(rng) * kMax;
    }
    samples.push_back({z, zs});
  }
  const BeamFit fit = fit_beam_mixture(samples, kMax);
  EXPECT_NEAR(fit.params.z_hit, truth.z_hit, 0.01);
  EXPECT_NEAR(fit.params.z_short, truth.z_short, 0.01);
  EXPECT_NEAR(fit.params.z_max, truth.z_max, 0.01);
  EXPECT_NEAR(fit.params.z_rand, truth.z_rand, 0.01);
  EXPECT_NEAR(fit.params.sigma_hit, truth.sigma_hit, 0.03 * truth.sigma_hit);
  EXPECT_NEAR(fit.params.lambda_short, truth.lambda_short, 0.1 * truth.lambda_short);
  EXPECT_GT(fit.quality.log_likelihood_after, fit.quality.log_likelihood_before);
}

TEST(CalibrateFits, LikelihoodFieldRecoversGaussianAndUniform) {
  constexpr double kMax = 2.0;  // distances clamped like the filter's field
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 0.05);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> d;
  for (int i = 0; i < 20000; ++i) d.push_back(u(rng) < 0.8 ? n(rng) : u(rng) * kMax);
  const FieldFit fit = fit_likelihood_field(d, kMax);
  EXPECT_NEAR(fit.params.z_hit, 0.8, 0.02);
  EXPECT_NEAR(fit.params.sigma_hit, 0.05, 0.005);
}

TEST(CalibrateFits, TooFewSamplesIsAnError) {
  EXPECT_THROW((void)fit_beam_mixture(std::vector<BeamSample>(10, {1.0, 1.0}), 10.0), Error);
  EXPECT_THROW((void)fit_odometry_noise(std::vector<MotionSample>(5)), Error);
}

// --- simulated logs with known parameters ----------------------------------------------------

struct Setting {
  const char* name;
  sim::OdometryAlphaNoise odometry;
  sim::RangeMixture ranges;
  std::uint64_t seed;
};

// Three robots: modest noise, noisy odometry (amcl's default magnitudes) and a wide range
// error, and biased odometry (5% long in distance, 5% short in rotation) with a sharp laser.
// (With more clutter in the noisy one, 15% short and 10% random readings, the filter's global
// localization from mote's defaults fails on this floor plan for seeds 2, 4, 5 and 6, so there
// is no trajectory to self-calibrate against.)
const Setting kSettings[] = {
    {"modest", {0.1, 0.02, 0.05, 0.02, 0.0, 0.0}, {0.8, 0.1, 0.05, 0.05, 0.05, 0.5}, 1},
    {"noisy", {0.2, 0.05, 0.1, 0.05, 0.0, 0.0}, {0.8, 0.1, 0.05, 0.05, 0.1, 1.0}, 2},
    {"biased", {0.05, 0.01, 0.03, 0.01, 0.05, -0.05}, {0.9, 0.04, 0.03, 0.03, 0.03, 0.3}, 3},
};

// The simulated log: 1.5 scans a second, so that every scan interval is one filter update (the
// alphas are defined per update: the variance of a sum of steps is not the model's variance of
// the summed step).
CalibrationOptions simulated(const Setting& s, const std::filesystem::path& dir,
                             double seconds = 600) {
  sim::SimulationConfig drive;
  drive.seconds = seconds;
  drive.scan_rate = 1.5;
  drive.seed = s.seed;
  drive.odometry_alphas = s.odometry;
  drive.range_mixture = s.ranges;
  const std::filesystem::path map = sim::bundled_map_path();
  const sim::SimulationFiles files =
      sim::write_simulation(sim::simulate(load_map(map), drive), dir, drive);
  CalibrationOptions o;
  o.map = map;
  o.log = files.log;
  o.config.update_min_d = 0.02;
  o.config.update_min_a = 0.02;
  o.reference = files.ground_truth;
  return o;
}

void expect_sensor_recovered(const Setting& s, const CalibrationRound& r) {
  const BeamMixture& b = r.beam.params;
  EXPECT_NEAR(b.sigma_hit, s.ranges.sigma_hit, 0.10 * s.ranges.sigma_hit) << s.name;
  EXPECT_NEAR(b.z_hit, s.ranges.z_hit, 0.05) << s.name;
  EXPECT_NEAR(b.z_short, s.ranges.z_short, 0.05) << s.name;
  EXPECT_NEAR(b.z_max, s.ranges.z_max, 0.05) << s.name;
  EXPECT_NEAR(b.z_rand, s.ranges.z_rand, 0.05) << s.name;
}

// The simulator draws every beam's error on its own, so the beams' correlation is nil and the
// tracking exponent the full product: measured tau 0.970-1.000 at the reference poses and
// 0.967-1.000 at the filter's own (rho_1 at most 0.01; the noisy robot's is the lowest).
void expect_independent_beams(const Setting& s, const CalibrationRound& r) {
  EXPECT_GT(r.correlation.tempering, 0.9) << s.name;
}

void expect_motion_recovered(const Setting& s, const CalibrationRound& r) {
  const OdometryAlphas& a = r.odometry.alphas;
  EXPECT_NEAR(a.alpha1, s.odometry.alpha1, 0.15 * s.odometry.alpha1) << s.name;
  EXPECT_NEAR(a.alpha2, s.odometry.alpha2, 0.15 * s.odometry.alpha2) << s.name;
  EXPECT_NEAR(a.alpha3, s.odometry.alpha3, 0.15 * s.odometry.alpha3) << s.name;
  EXPECT_NEAR(a.alpha4, s.odometry.alpha4, 0.15 * s.odometry.alpha4) << s.name;
  // The biases' standard error with 900 increments is about 0.01 at the noisy setting's
  // rotation noise (sqrt(alpha1) / sqrt(900) of the rotation): 3 of it.
  EXPECT_NEAR(r.odometry.translation_bias, s.odometry.translation_bias, 0.03) << s.name;
  EXPECT_NEAR(r.odometry.rotation_bias, s.odometry.rotation_bias, 0.03) << s.name;
}

// The recovery tests check the rounds' fits, which the margin search after them does not touch
// (its tracking runs are most of a calibration's time); ConfigLoadsAndCarriesTheFitAndTheStarting-
// Config runs it.
TEST(CalibrateSimulated, RecoversKnownParametersWithReference) {
  for (const Setting& s : kSettings) {
    CalibrationOptions o = simulated(s, test::temp_dir() / s.name);
    o.search_margin = false;
    const CalibrationResult r = calibrate(o);
    ASSERT_EQ(r.rounds.size(), 1U);
    expect_sensor_recovered(s, r.rounds.back());
    expect_motion_recovered(s, r.rounds.back());
    expect_independent_beams(s, r.rounds.back());
  }
}

// Without the reference the filter's own trajectory stands in, and its poses' position noise
// (1-1.5 cm) costs the odometry fit information: at 900 increments alpha2's and alpha4's standard
// errors are 6% and 15-20% of them and the bounds one to two standard errors (docs/
// calibration.md), so these logs are three times as long (2700 scans): their errors are 0.64-0.86
// of those against the reference at 900 (modest robot). What the longer log cannot fix, a
// systematic shift, the fit must not have: the rotation scale error comes from the heading
// channel and alpha4's turns from the odometry's split of the rotation
// (calibrate_motion_fit.cpp).
TEST(CalibrateSimulated, RecoversKnownParametersWithoutReference) {
  for (const Setting& s : kSettings) {
    CalibrationOptions o = simulated(s, test::temp_dir() / s.name, 1800);
    o.reference.clear();
    o.search_margin = false;
    const CalibrationResult r = calibrate(o);
    EXPECT_FALSE(r.with_reference);
    EXPECT_TRUE(r.margins.empty());
    expect_sensor_recovered(s, r.rounds.back());
    expect_motion_recovered(s, r.rounds.back());
    expect_independent_beams(s, r.rounds.back());
  }
}

// The written file alone reproduces the calibrated filter: the fit, and the starting config's
// values the fit does not set. A fixed likelihood_tempering gives way to the fitted tracking
// exponent (validate() refuses the two together).
TEST(CalibrateSimulated, ConfigLoadsAndCarriesTheFitAndTheStartingConfig) {
  CalibrationOptions o = simulated(kSettings[0], test::temp_dir());
  o.config.max_beams = 48;
  o.config.unmapped_obstacle_filter = false;
  o.config.update_min_d = 0.15;
  o.config.likelihood_tempering = 0.5;
  const CalibrationResult r = calibrate(o);
  const std::filesystem::path yaml = write_calibration(r, test::temp_dir() / "out");
  const LoadedConfig loaded = load_config(yaml);
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_NEAR(loaded.config.z_hit, r.config.z_hit, 1e-5);
  EXPECT_NEAR(loaded.config.sigma_hit, r.config.sigma_hit, 1e-5 * r.config.sigma_hit);
  EXPECT_NEAR(loaded.config.alpha3, r.config.alpha3, 1e-5 * r.config.alpha3);
  EXPECT_NEAR(loaded.config.tracking_tempering, r.config.tracking_tempering, 1e-5);
  EXPECT_EQ(loaded.config.max_beams, 48);
  EXPECT_FALSE(loaded.config.unmapped_obstacle_filter);
  EXPECT_DOUBLE_EQ(loaded.config.update_min_d, 0.15);
  EXPECT_DOUBLE_EQ(loaded.config.likelihood_tempering, 0.0);
  // The margin search ran tracking runs and the config takes the best of them.
  ASSERT_GE(r.margins.size(), 2U);
  EXPECT_EQ(r.margins.front().margin, LocalizerConfig{}.motion_noise_margin);
  EXPECT_GT(r.margins.front().poses, 100U);
  EXPECT_DOUBLE_EQ(loaded.config.motion_noise_margin, best_margin(r.margins).margin);
  const std::string text = test::read_bytes(yaml);
  EXPECT_NE(text.find("fixed likelihood_tempering (0.5) is dropped"), std::string::npos);
  EXPECT_TRUE(std::filesystem::file_size(yaml.parent_path() / "calibration.png") > 1000);
  EXPECT_NE(text.find("log-likelihood"), std::string::npos);
  // Every alpha's standard error, none held at a bound on this robot.
  const OdometryAlphas& se = r.rounds.back().odometry.alphas_zero_mean_se;
  EXPECT_GT(std::min({se.alpha1, se.alpha2, se.alpha3, se.alpha4}), 0.0);
  EXPECT_NE(text.find("# Standard errors (observed information): alpha1 "), std::string::npos);
}

/// With an Ackermann config the config carries the Ackermann fit in the model's alphas (alpha1
/// steering, alpha3 distance) and says what they are. The simulated robot turns on the spot,
/// so only its arcs are used; recovery is CalibrateAckermann's, on draws from the model.
TEST(CalibrateSimulated, AckermannConfigCarriesTheArcFit) {
  CalibrationOptions o = simulated(kSettings[0], test::temp_dir());
  o.config.odom_model_type = OdomModel::kAckermann;
  o.config.wheelbase = 0.8;
  const CalibrationResult r = calibrate(o);
  const CalibrationRound& f = r.rounds.back();
  ASSERT_TRUE(f.ackermann.has_value());
  EXPECT_GT(f.ackermann->quality.samples, 100U);
  EXPECT_LT(f.ackermann->quality.samples, f.odometry.quality.samples);
  const std::filesystem::path yaml = write_calibration(r, test::temp_dir() / "ackermann");
  const LoadedConfig loaded = load_config(yaml);
  EXPECT_EQ(loaded.config.odom_model_type, OdomModel::kAckermann);
  EXPECT_DOUBLE_EQ(loaded.config.wheelbase, o.config.wheelbase);  // the fit's geometry
  EXPECT_TRUE(r.margins.empty());  // the online noise estimate is the diff model's only
  EXPECT_NEAR(loaded.config.alpha1, f.ackermann->alpha_steering, 1e-5 * loaded.config.alpha1);
  EXPECT_NEAR(loaded.config.alpha3, f.ackermann->alpha_distance, 1e-5 * loaded.config.alpha3);
  EXPECT_NE(test::read_bytes(yaml).find("Ackermann (bicycle"), std::string::npos);
}

// --- bad input -----------------------------------------------------------------------------

std::string error_of(const CalibrationOptions& o) {
  try {
    (void)calibrate(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CalibrateBadInput, ShortLogNoOdometryAndNoConvergence) {
  sim::SimulationConfig drive;
  drive.seconds = 10;
  const std::filesystem::path map = sim::bundled_map_path();
  const OccupancyGrid grid = load_map(map);
  const std::filesystem::path dir = test::temp_dir();
  CalibrationOptions o;
  o.map = map;
  o.log = sim::write_simulation(sim::simulate(grid, drive), dir / "short").log;
  EXPECT_NE(error_of(o).find("log too short"), std::string::npos) << error_of(o);

  drive.seconds = 120;
  sim::Simulation still = sim::simulate(grid, drive);
  for (logs::ScanFrame& f : still.frames) f.odometry = still.frames.front().odometry;
  o.log = dir / "still.clf";
  logs::write_carmen_log(o.log, still.frames);
  EXPECT_NE(error_of(o).find("no odometry"), std::string::npos) << error_of(o);

  // Every reading a no-return: no scan ever places the robot.
  sim::Simulation blind = sim::simulate(grid, drive);
  for (logs::ScanFrame& f : blind.frames) {
    for (float& z : f.scan.ranges) z = f.scan.range_max;
  }
  o.log = dir / "blind.clf";
  logs::write_carmen_log(o.log, blind.frames);
  EXPECT_NE(error_of(o).find("never converged"), std::string::npos) << error_of(o);
}

}  // namespace
}  // namespace mote::calibrate
