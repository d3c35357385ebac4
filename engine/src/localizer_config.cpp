#include <cmath>
#include <string>

#include "mote/core/error.hpp"
#include "mote/engine/localizer_config.hpp"

namespace mote {

namespace {

void require(bool ok, const char* field, const std::string& expected) {
  if (!ok) throw ConfigError(std::string("LocalizerConfig.") + field + ": expected " + expected);
}

bool finite_at_least(double v, double lo) { return std::isfinite(v) && v >= lo; }
bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }
bool probability(double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; }

// Counts that size allocations (particle store, task arena): beyond these a config is more
// likely corrupt than meant, and would exhaust memory instead of failing with a message.
constexpr int kMaxParticles = 100'000'000;
constexpr int kMaxThreads = 1024;

void validate_particles(const LocalizerConfig& c) {
  require(c.min_particles >= 1, "min_particles", "at least 1");
  require(c.max_particles >= c.min_particles, "max_particles", "at least min_particles");
  require(c.max_particles <= kMaxParticles, "max_particles",
          "at most " + std::to_string(kMaxParticles) + " particles");
  require(finite_positive(c.pf_err) && c.pf_err < 1.0, "pf_err", "a value in (0, 1)");
  if (c.kld_z_is_quantile) {
    require(finite_positive(c.pf_z), "pf_z", "a positive normal quantile");
  } else {
    require(finite_positive(c.pf_z) && c.pf_z < 1.0, "pf_z", "a probability in (0, 1)");
  }
  require(finite_positive(c.kld_bin_xy), "kld_bin_xy", "a positive bin size in metres");
  require(finite_positive(c.kld_bin_theta), "kld_bin_theta", "a positive bin size in radians");
  require(finite_at_least(c.global_particles_per_bin, 0.0), "global_particles_per_bin",
          "a count >= 0 (0 draws max_particles)");
}

void validate_resampling(const LocalizerConfig& c) {
  require(c.resample_interval >= 1, "resample_interval", "at least 1");
  require(finite_positive(c.resample_ess_fraction) && c.resample_ess_fraction <= 1.0,
          "resample_ess_fraction", "a fraction in (0, 1]");
  require(probability(c.recovery_alpha_slow), "recovery_alpha_slow", "a rate in [0, 1]");
  require(probability(c.recovery_alpha_fast), "recovery_alpha_fast", "a rate in [0, 1]");
  require(std::isfinite(c.lost_misfit) && c.lost_misfit > 0.0 && c.lost_misfit < 2.0, "lost_misfit",
          "a share in (0, 2)");
  // Thrun table 8.3: 0 <= alpha_slow << alpha_fast. Either at 0 disables injection (amcl).
  require(c.recovery_alpha_slow == 0.0 || c.recovery_alpha_fast == 0.0 ||
              c.recovery_alpha_slow < c.recovery_alpha_fast,
          "recovery_alpha_slow", "a rate below recovery_alpha_fast (Thrun table 8.3)");
  require(finite_at_least(c.update_min_d, 0.0), "update_min_d", "a distance >= 0");
  require(finite_at_least(c.update_min_a, 0.0), "update_min_a", "an angle >= 0");
  require(finite_positive(c.odom_jump_max_d), "odom_jump_max_d", "a positive distance in metres");
}

void validate_motion(const LocalizerConfig& c) {
  require(finite_at_least(c.alpha1, 0.0), "alpha1", "a value >= 0");
  require(finite_at_least(c.alpha2, 0.0), "alpha2", "a value >= 0");
  require(finite_at_least(c.alpha3, 0.0), "alpha3", "a value >= 0");
  require(finite_at_least(c.alpha4, 0.0), "alpha4", "a value >= 0");
  require(finite_at_least(c.alpha5, 0.0), "alpha5", "a value >= 0");
  require(finite_positive(c.wheelbase), "wheelbase", "a positive length in metres");
  require(finite_positive(c.motion_noise_margin), "motion_noise_margin",
          "a positive variance factor");
}

void validate_sensor(const LocalizerConfig& c) {
  require(c.max_beams >= 1, "max_beams", "at least 1");
  require(finite_at_least(c.z_hit, 0.0), "z_hit", "a weight >= 0");
  require(finite_at_least(c.z_short, 0.0), "z_short", "a weight >= 0");
  require(finite_at_least(c.z_max, 0.0), "z_max", "a weight >= 0");
  require(finite_at_least(c.z_rand, 0.0), "z_rand", "a weight >= 0");
  require(c.z_hit + c.z_short + c.z_max + c.z_rand > 0.0, "z_hit", "mixture weights not all 0");
  require(finite_positive(c.sigma_hit), "sigma_hit", "a positive length in metres");
  require(finite_positive(c.lambda_short), "lambda_short", "a positive rate in 1/m");
  require(finite_positive(c.laser_likelihood_max_dist), "laser_likelihood_max_dist",
          "a positive distance in metres");
  require(std::isfinite(c.likelihood_tempering) && c.likelihood_tempering >= 0.0 &&
              c.likelihood_tempering <= 1.0,
          "likelihood_tempering", "an exponent in (0, 1], or 0 to choose it per update");
  require(std::isfinite(c.tracking_tempering) && c.tracking_tempering >= 0.0 &&
              c.tracking_tempering <= 1.0,
          "tracking_tempering", "an exponent in (0, 1], or 0 for none");
  // tracking_tempering replaces the adaptive search once the belief has settled; with a fixed
  // exponent there is no search to replace and it would be silently ignored.
  require(c.tracking_tempering == 0.0 || c.likelihood_tempering == 0.0, "tracking_tempering",
          "0 when likelihood_tempering fixes the exponent (it replaces the adaptive search of "
          "likelihood_tempering: 0 once the belief has settled; nav2's defaults fix it at 1)");
  require(finite_positive(c.tempering_ess_fraction) && c.tempering_ess_fraction < 1.0,
          "tempering_ess_fraction", "a fraction in (0, 1)");
  require(std::isfinite(c.laser_min_range), "laser_min_range", "a finite number");
  require(std::isfinite(c.laser_max_range), "laser_max_range", "a finite number");
  require(c.range_table_angles >= 32 && c.range_table_angles % 32 == 0, "range_table_angles",
          "a positive multiple of 32");
  // Up to 1 TB: beyond any machine this runs on, and safe to convert to bytes.
  require(finite_positive(c.range_table_budget_mb) && c.range_table_budget_mb <= 1048576.0,
          "range_table_budget_mb", "a positive number of megabytes, at most 1048576");
}

}  // namespace

LocalizerConfig nav2_defaults() {
  LocalizerConfig c;
  c.max_particles = 2000;
  c.global_particles_per_bin = 0.0;
  c.recovery_alpha_slow = 0.0;
  c.recovery_alpha_fast = 0.0;
  c.likelihood_tempering = 1.0;
  c.adaptive_motion_noise = false;
  c.unmapped_obstacle_filter = false;
  c.relocalize_when_lost = false;
  c.lost_misfit_learned = false;
  c.unknown_cells_block_rays = true;
  c.ray_casting = RayCasting::kExact;  // amcl's map_calc_range casts every ray
  // amcl's formulas: 1 + sum pz^3 for both models, a resample at every update
  // (resample_interval 1, no ESS gate), and pf_z read as the quantile itself.
  c.likelihood_combination = LikelihoodCombination::kAmclCubedSum;
  c.resample_ess_fraction = 1.0;
  c.kld_z_is_quantile = true;
  return c;
}

void LocalizerConfig::validate() const {
  validate_particles(*this);
  validate_resampling(*this);
  validate_motion(*this);
  validate_sensor(*this);
  require(threads >= 0 && threads <= kMaxThreads, "threads",
          "a thread count in [0, " + std::to_string(kMaxThreads) + "] (0 = every core)");
  require(grain >= 1, "grain", "at least 1 particle per task");
}

}  // namespace mote
