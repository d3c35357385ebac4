#pragma once
// The beam model's mixture (Thrun et al., table 6.1, eqs. 6.4-6.11) in float for one reading z
// and many expected ranges z*, branch-free so the loop over particles vectorizes
// (engine-internal). sensor_formulas.cpp holds the scalar double reference, beam_log_likelihood.
//
// Accuracy for 0 <= z* <= z_max: every factor is within a few float ulp of the double formula
// (the polynomials of beam_float_math.hpp are within 2e-7 relative), so the mixture is within
// 1e-6 relative and its log within 1e-6 * (1 + |log p|) of beam_log_likelihood.

#include "beam_float_math.hpp"
#include "mote/engine/sensor_model.hpp"

namespace mote::detail {

// Everything of the mixture that depends only on the reading z (0 <= z <= z_max, z_max for a
// max-range reading) and the parameters: computed once per beam per scan, in double, then
// rounded.
struct BeamTerms {
  float z;                // m, the reading
  float range_max;        // m, z_max
  float base;             // the term without z*: z_rand / z_max (eq. 6.11) for z < z_max,
                          // z_max's weight (eq. 6.10, p_rand being 0) for z = z_max
  float hit_scale;        // z_hit / (sqrt(2 pi) sigma_hit) (eq. 6.4)
  float hit_exponent;     // -1 / (2 sigma_hit^2)
  float inv_sigma_sqrt2;  // 1 / (sigma_hit sqrt 2): erfc's argument scale (eq. 6.6)
  float tail_low;         // m, 6 sigma_hit: beyond it (and below tail_high) eq. 6.6's
  float tail_high;        // m, z_max - 6 sigma_hit    normalizer is 1 to within 2e-9
  float short_scale;      // z_short lambda exp(-lambda z) (eq. 6.7)
  float lambda;           // 1/m, lambda_short
};

[[nodiscard]] BeamTerms beam_terms(float z, float range_max, const MixtureParams& p) noexcept;

// Whether the float polynomials stay in their domain for every z* in [0, z_max]: every term
// finite and (z - z*)^2 and the erfc arguments representable. Absurd parameters (sigma_hit below
// 1e-19 m, say) fail this and take the scalar double path.
[[nodiscard]] bool float_terms_usable(const BeamTerms& t) noexcept;

// Which tails of the hit Gaussian a batch of z* needs for eq. 6.6's normalizer.
enum class Tails {
  kNone,  // every z* farther than 6 sigma from 0 and z_max: the normalizer is 1, as in
          // beam_log_likelihood
  kNear,  // the tail nearer z*: z_max >= 12 sigma, so the other tail is below 2e-9 and does
          // not change the mass in float (an ulp of it is 6e-8)
  kBoth,  // z_max < 12 sigma: both tails, as beam_log_likelihood computes them
};

// The hit Gaussian's mass on [0, z_max] (eq. 6.6): 1 - Phi(-z* / sigma) - Phi((z* - z_max) / sigma)
// with Phi(-x) = erfc(x / sqrt 2) / 2.
template <Tails kTails>
[[nodiscard]] inline float hit_mass(const BeamTerms& t, float z_star) noexcept {
  const float low = z_star * t.inv_sigma_sqrt2;
  const float high = (t.range_max - z_star) * t.inv_sigma_sqrt2;
  if constexpr (kTails == Tails::kNone) {
    return 1.0F;
  } else if constexpr (kTails == Tails::kNear) {
    return 1.0F - 0.5F * erfc_nonneg(low < high ? low : high);
  } else {
    return 1.0F - 0.5F * erfc_sum(low, high);
  }
}

// p(z | z*) of table 6.1 (eq. 6.12) for 0 <= z* <= z_max.
template <Tails kTails>
[[nodiscard]] inline float beam_mixture(const BeamTerms& t, float z_star) noexcept {
  const float d = t.z - z_star;
  const float gaussian = t.hit_scale * exp_nonpositive(t.hit_exponent * d * d);  // eq. 6.4
  const float mass = hit_mass<kTails>(t, z_star);                                // eq. 6.6
  // eqs. 6.7-6.9: the exponential truncated at z*, its normalizer 1 - exp(-lambda z*).
  const bool is_short = t.z <= z_star && z_star > 0.0F;
  const float short_mass = select(is_short, -expm1_nonpositive(-t.lambda * z_star), 1.0F);
  const float short_density = select(is_short, t.short_scale, 0.0F);
  // gaussian / mass + short_density / short_mass over one division.
  return t.base + (gaussian * short_mass + short_density * mass) / (mass * short_mass);
}

}  // namespace mote::detail
