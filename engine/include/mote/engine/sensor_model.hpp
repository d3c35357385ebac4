#pragma once
/// \file
/// The measurement side of MCL: the concept every sensor model meets, the parallel deterministic
/// kernel that applies one, and the mixture formulas of Thrun et al., chapter 6, in the log domain.

#include <concepts>
#include <cstddef>

#include "mote/engine/beams.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/weights.hpp"

namespace mote {

/// A sensor model: weigh(beams, particles, begin, end) adds tau * log p(z | x_i) to
/// particles.logw[i] for every i in [begin, end) and touches nothing else. It runs on many
/// threads at once, so it must be const-callable and reentrant. Implement it to plug a custom
/// model into Localizer-style loops with `weigh_scan`.
template <class S>
concept SensorModel = requires(const S& model, const BeamSet& beams, const ParticleView& particles,
                               std::size_t begin, std::size_t end) {
  { model.weigh(beams, particles, begin, end) } -> std::same_as<void>;
};

/// Applies a sensor model to every particle, in parallel chunks whose boundaries depend only on
/// the particle count and grain (bit-identical for any thread count).
template <SensorModel S>
void weigh_scan(const S& model, const BeamSet& beams, const ParticleView& particles,
                std::size_t grain = kDefaultGrain) {
  reweight_chunks(
      particles,
      [&](const ParticleView& p, std::size_t begin, std::size_t end) {
        model.weigh(beams, p, begin, end);
      },
      grain);
}

/// Mixture parameters shared by the beam and likelihood-field models (amcl names).
struct MixtureParams {
  double z_hit = 0.5;         ///< weight of the measurement Gaussian
  double z_short = 0.05;      ///< weight of unexpected short readings (beam model only)
  double z_max = 0.05;        ///< weight of max-range readings
  double z_rand = 0.5;        ///< weight of uniform random readings
  double sigma_hit = 0.2;     ///< m, std. dev. of the measurement Gaussian
  double lambda_short = 0.1;  ///< 1/m, decay of the short-reading exponential
};

/// log p(z | z*) of the beam model, Thrun table 6.1 / eqs. 6.4-6.10: the mixture of
/// p_hit (Gaussian around the expected range z*, normalized over [0, z_max]), p_short
/// (exponential truncated at z*), p_max (point mass at z_max) and p_rand (uniform over [0, z_max)).
/// z >= range_max is a max-range reading, evaluated at z = z_max as eq. 6.12 says: z_max plus
/// z_hit p_hit(z_max) plus z_short p_short(z_max) (non-zero only for z* = z_max), p_rand being 0
/// there. Returns -inf only when every term is 0, NaN for a NaN z*.
[[nodiscard]] double beam_log_likelihood(double z, double z_expected, double range_max,
                                         const MixtureParams& p) noexcept;

/// The likelihood-field density of one beam endpoint at distance d (m) from the nearest obstacle,
/// Thrun table 6.3 line 8: z_hit * N(d; 0, sigma_hit^2) + z_rand / z_max.
[[nodiscard]] double likelihood_field_density(double d, double range_max,
                                              const MixtureParams& p) noexcept;

/// ROS amcl's likelihood-field beam term: z_hit * exp(-d^2 / (2 sigma^2)) + z_rand / z_max
/// (an unnormalized Gaussian), which amcl combines as 1 + sum(pz^3).
[[nodiscard]] double amcl_likelihood_field_pz(double d, double range_max,
                                              const MixtureParams& p) noexcept;

/// ROS amcl's beam-model term for reading z where the map expects z_star (amcl_laser.cpp,
/// BeamModel): z_hit exp(-(z - z*)^2 / (2 sigma^2)) (unnormalized), plus z_short lambda
/// exp(-lambda z) when z < z*, plus z_max at z = z_max, plus z_rand / z_max below it; amcl
/// combines the terms as 1 + sum(pz^3).
[[nodiscard]] double amcl_beam_pz(double z, double z_star, double range_max,
                                  const MixtureParams& p) noexcept;

}  // namespace mote
