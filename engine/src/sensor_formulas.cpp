// The per-beam formulas of Thrun et al., Probabilistic Robotics, chapter 6.
#include <cmath>
#include <numbers>

#include "mote/engine/sensor_model.hpp"

namespace mote {

namespace {

double normal_cdf(double x) noexcept { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

// eta of eq. 6.6: 1 / integral over [0, z_max] of N(z; z*, sigma^2). Inside [6 sigma, z_max -
// 6 sigma] the integral is 1 to within 1e-9, so the two erfc calls are skipped there.
double hit_normalizer(double z_expected, double range_max, double sigma) noexcept {
  if (z_expected > 6.0 * sigma && z_expected < range_max - 6.0 * sigma) return 1.0;
  const double mass =
      normal_cdf((range_max - z_expected) / sigma) - normal_cdf(-z_expected / sigma);
  return mass > 0.0 ? 1.0 / mass : 0.0;
}

double gaussian_density(double d, double sigma) noexcept {
  return std::exp(-0.5 * d * d / (sigma * sigma)) / (std::sqrt(2.0 * std::numbers::pi) * sigma);
}

}  // namespace

double beam_log_likelihood(double z, double z_expected, double range_max,
                           const MixtureParams& p) noexcept {
  // A reading at or beyond z_max is a max-range reading, table 6.1 at z = z_max: p_max is 1
  // there (eq. 6.10) and p_rand 0 (eq. 6.11, uniform on [0, z_max)), but p_hit (eq. 6.4, on
  // [0, z_max]) and p_short (eq. 6.7, on [0, z*]) are still evaluated, so a particle expecting a
  // wall well short of z_max is penalized for a "no return" (as in amcl's beam model).
  const bool max_range = z >= range_max;
  if (max_range) z = range_max;
  double sum = max_range ? p.z_max : p.z_rand / range_max;  // eqs. 6.10, 6.11
  if (z >= 0.0) {
    sum += p.z_hit * hit_normalizer(z_expected, range_max, p.sigma_hit) *
           gaussian_density(z - z_expected, p.sigma_hit);  // eqs. 6.4-6.6
  }
  if (z >= 0.0 && z <= z_expected && z_expected > 0.0) {
    // eq. 6.9. expm1, not 1 - exp: for lambda z* below 1e-16 the subtraction gives 0, and eta
    // became inf (log p = +inf, or NaN with z_short = 0) for a particle touching a wall.
    const double eta = -1.0 / std::expm1(-p.lambda_short * z_expected);
    sum += p.z_short * eta * p.lambda_short * std::exp(-p.lambda_short * z);  // eq. 6.7
  }
  return std::log(sum);
}

double likelihood_field_density(double d, double range_max, const MixtureParams& p) noexcept {
  return p.z_hit * gaussian_density(d, p.sigma_hit) + p.z_rand / range_max;
}

double amcl_likelihood_field_pz(double d, double range_max, const MixtureParams& p) noexcept {
  return p.z_hit * std::exp(-0.5 * d * d / (p.sigma_hit * p.sigma_hit)) + p.z_rand / range_max;
}

double amcl_beam_pz(double z, double z_star, double range_max, const MixtureParams& p) noexcept {
  const double miss = z - z_star;
  double pz = p.z_hit * std::exp(-0.5 * miss * miss / (p.sigma_hit * p.sigma_hit));
  if (miss < 0.0) pz += p.z_short * p.lambda_short * std::exp(-p.lambda_short * z);
  pz += z >= range_max ? p.z_max : p.z_rand / range_max;
  return pz;
}

}  // namespace mote
