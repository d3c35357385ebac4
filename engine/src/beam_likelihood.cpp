// The beam model's scan likelihood over cast expected ranges (Thrun et al., table 6.1), batched:
// what depends on a beam's reading alone is computed once per beam, then the loop runs
// beam-outer over blocks of particles, vectorized over the particles of a block. The block loop
// is compiled per instruction set and dispatched (isa_target.hpp): everything it calls is
// always inlined into it.
#include "beam_likelihood.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/core/isa_target.hpp"
#include "mote/engine/beam_model.hpp"

namespace mote {

namespace detail {

BeamTerms beam_terms(float z, float range_max, const MixtureParams& p) noexcept {
  const double sigma = p.sigma_hit;
  const double lambda = p.lambda_short;
  const bool max_range = z >= range_max;
  if (max_range) z = range_max;
  return {.z = z,
          .range_max = range_max,
          .base = static_cast<float>(max_range ? p.z_max : p.z_rand / range_max),
          .hit_scale = static_cast<float>(p.z_hit / (std::sqrt(2.0 * std::numbers::pi) * sigma)),
          .hit_exponent = static_cast<float>(-0.5 / (sigma * sigma)),
          .inv_sigma_sqrt2 = static_cast<float>(1.0 / (sigma * std::numbers::sqrt2)),
          .tail_low = static_cast<float>(6.0 * sigma),
          .tail_high = static_cast<float>(range_max - 6.0 * sigma),
          .short_scale = static_cast<float>(p.z_short * lambda * std::exp(-lambda * z)),
          .lambda = static_cast<float>(lambda)};
}

bool float_terms_usable(const BeamTerms& t) noexcept {
  const float widest_erfc_argument = t.range_max * t.inv_sigma_sqrt2;
  return std::isfinite(t.range_max * t.range_max) &&
         std::isfinite(widest_erfc_argument * widest_erfc_argument) && std::isfinite(t.base) &&
         std::isfinite(t.hit_scale) && std::isfinite(t.hit_exponent) && t.hit_exponent < 0.0F &&
         std::isfinite(t.short_scale) && std::isfinite(t.lambda);
}

}  // namespace detail

namespace {

// Particles per block: one beam's z* and the block's running sums stay in L1, and so do the
// block's rows of the particle-major range array (128 x 60 floats = 30 KB) across its beams.
constexpr std::size_t kBlock = 128;

// The float path covers mixtures in [2^-90, 2^90]. Below, z_rand is (nearly) 0 and float's
// range could lose the Gaussian's far tail that double keeps; above, z* is subnormal and the
// short-reading normalizer overflows. Those lanes, and every z* outside [0, z_max] (NaN from a
// non-finite pose), are recomputed by beam_log_likelihood.
constexpr float kMinMixture = 0x1p-90F;
constexpr float kMaxMixture = 0x1p90F;

// How one beam is weighed, decided once per call from its reading alone.
struct BeamPlan {
  enum class Kind {
    kConstant,  // z < 0 or NaN (p_rand only): the same for every z*
    kFloat,     // the vectorized float mixture (z >= z_max taken as z_max)
    kExact,     // beam_log_likelihood for every particle (parameters float cannot hold)
  };
  Kind kind;
  float z;                  // m, the reading
  double constant;          // kConstant: log p(z | z*)
  detail::BeamTerms terms;  // kFloat
};

BeamPlan plan_beam(float z, float range_max, const MixtureParams& p) {
  if (!(z >= 0.0F)) {
    return {BeamPlan::Kind::kConstant, z, beam_log_likelihood(z, 0.0, range_max, p), {}};
  }
  // A max-range reading depends on z* too (p_hit and p_short at z_max, eq. 6.12).
  const float reading = z < range_max ? z : range_max;
  const detail::BeamTerms terms = detail::beam_terms(reading, range_max, p);
  const bool usable = detail::float_terms_usable(terms);
  return {usable ? BeamPlan::Kind::kFloat : BeamPlan::Kind::kExact, reading, 0.0, terms};
}

struct Block {
  alignas(64) float z_star[kBlock];        // m, one beam's expected ranges
  alignas(64) double sum[kBlock];          // log p(z | x) over the beams so far
  alignas(64) std::int32_t exact[kBlock];  // 1: lane needs beam_log_likelihood
  std::size_t count = 0;                   // particles in the block
  std::size_t lanes = 0;                   // count padded to 16: padding lanes are dropped
};

// z* of beam b for the block's particles (a strided gather from the block's rows of the
// particle-major array), padded with z_max / 2, a valid range.
MOTE_ALWAYS_INLINE void gather_beam(const float* expected, std::size_t beams, std::size_t b,
                                    float range_max, Block& block) {
  for (std::size_t k = 0; k < block.count; ++k) block.z_star[k] = expected[k * beams + b];
  std::fill(block.z_star + block.count, block.z_star + block.lanes, 0.5F * range_max);
}

// Which tails of eq. 6.6's normalizer this beam's z* need (see detail::Tails).
MOTE_ALWAYS_INLINE detail::Tails tails_needed(const detail::BeamTerms& t, const float* z_star,
                                              std::size_t lanes) {
  std::int32_t near_an_end = 0;
  for (std::size_t k = 0; k < lanes; ++k) {
    const bool inside = (z_star[k] > t.tail_low) & (z_star[k] < t.tail_high);
    near_an_end |= inside ? 0 : 1;
  }
  if (near_an_end == 0) return detail::Tails::kNone;
  return t.range_max < 2.0F * t.tail_low ? detail::Tails::kBoth : detail::Tails::kNear;
}

// Adds the float mixture's log to every lane in its domain and flags the others in exact.
// Branch-free: the loop vectorizes. The terms come by value so that no store can alias them.
template <detail::Tails kTails>
MOTE_ALWAYS_INLINE void add_float_lanes(const detail::BeamTerms t, const float* z_star, double* sum,
                                        std::int32_t* exact, std::size_t lanes) {
  for (std::size_t k = 0; k < lanes; ++k) {
    const bool in_range = z_star[k] >= 0.0F && z_star[k] <= t.range_max;  // false for NaN
    const float mixture = detail::beam_mixture<kTails>(t, in_range ? z_star[k] : 0.0F);
    const bool ok = in_range && mixture >= kMinMixture && mixture <= kMaxMixture;
    sum[k] += ok ? static_cast<double>(detail::log_normal(ok ? mixture : 1.0F)) : 0.0;
    exact[k] = ok ? 0 : 1;
  }
}

// The float path for one beam; returns whether any lane was flagged for the exact formula.
MOTE_ALWAYS_INLINE bool add_float_lanes(const detail::BeamTerms& t, Block& block) {
  const float* z_star = block.z_star;
  switch (tails_needed(t, z_star, block.lanes)) {
    case detail::Tails::kNone:
      add_float_lanes<detail::Tails::kNone>(t, z_star, block.sum, block.exact, block.lanes);
      break;
    case detail::Tails::kNear:
      add_float_lanes<detail::Tails::kNear>(t, z_star, block.sum, block.exact, block.lanes);
      break;
    case detail::Tails::kBoth:
      add_float_lanes<detail::Tails::kBoth>(t, z_star, block.sum, block.exact, block.lanes);
      break;
  }
  // A separate pass: GCC 12 does not vectorize the loops above with this reduction in them.
  std::int32_t flagged = 0;
  for (std::size_t k = 0; k < block.lanes; ++k) flagged |= block.exact[k];
  return flagged != 0;
}

MOTE_ALWAYS_INLINE void add_exact_lanes(float z, float range_max, const MixtureParams& p,
                                        Block& block) {
  for (std::size_t k = 0; k < block.lanes; ++k) {
    if (block.exact[k] != 0) block.sum[k] += beam_log_likelihood(z, block.z_star[k], range_max, p);
  }
}

MOTE_ALWAYS_INLINE void add_beam(const BeamPlan& plan, float range_max, const MixtureParams& p,
                                 Block& block) {
  switch (plan.kind) {
    case BeamPlan::Kind::kConstant:
      for (std::size_t k = 0; k < block.lanes; ++k) block.sum[k] += plan.constant;
      break;
    case BeamPlan::Kind::kFloat:
      if (add_float_lanes(plan.terms, block)) add_exact_lanes(plan.z, range_max, p, block);
      break;
    case BeamPlan::Kind::kExact:
      std::fill(block.exact, block.exact + block.lanes, 1);
      add_exact_lanes(plan.z, range_max, p, block);
      break;
  }
}

MOTE_ALWAYS_INLINE void weigh_block(const std::vector<BeamPlan>& plans, float range_max,
                                    const float* expected, const BeamModelParams& params,
                                    float* logw, std::size_t count) {
  Block block;
  block.count = count;
  block.lanes = pad_particles(count);
  std::fill(block.sum, block.sum + block.lanes, 0.0);
  for (std::size_t b = 0; b < plans.size(); ++b) {
    gather_beam(expected, plans.size(), b, range_max, block);
    add_beam(plans[b], range_max, params.mixture, block);
  }
  for (std::size_t k = 0; k < count; ++k) {
    logw[k] += static_cast<float>(params.tempering * block.sum[k]);
  }
}

MOTE_ISA_VARIANTS(weigh_block, weigh_block,
                  (const std::vector<BeamPlan>& plans, float range_max, const float* expected,
                   const BeamModelParams& params, float* logw, std::size_t count),
                  (plans, range_max, expected, params, logw, count))

// amcl's combination, log(1 + sum_b pz_b^3) per particle (nav2_amcl's defaults): scalar, as
// amcl computes it; the mote defaults take the vectorized product above.
void add_amcl_cubed_sums(std::span<const float> ranges, float range_max,
                         std::span<const float> expected, const BeamModelParams& params,
                         std::span<float> logw) {
  const std::size_t beams = ranges.size();
  for (std::size_t i = 0; i < logw.size(); ++i) {
    double sum = 0.0;
    for (std::size_t b = 0; b < beams; ++b) {
      const double z = std::min(ranges[b], range_max);
      const double pz = amcl_beam_pz(z, expected[i * beams + b], range_max, params.mixture);
      sum += pz * pz * pz;
    }
    logw[i] += static_cast<float>(params.tempering * std::log1p(sum));
  }
}

}  // namespace

void add_beam_log_likelihoods(std::span<const float> ranges, float range_max,
                              std::span<const float> expected, const BeamModelParams& params,
                              std::span<float> logw) {
  if (expected.size() != logw.size() * ranges.size()) {
    throw ConfigError("add_beam_log_likelihoods: expected ranges hold " +
                      std::to_string(expected.size()) + " values, not particles x beams = " +
                      std::to_string(logw.size()) + " x " + std::to_string(ranges.size()));
  }
  if (params.combination == LikelihoodCombination::kAmclCubedSum) {
    add_amcl_cubed_sums(ranges, range_max, expected, params, logw);
    return;
  }
  std::vector<BeamPlan> plans;
  plans.reserve(ranges.size());
  for (const float z : ranges) plans.push_back(plan_beam(z, range_max, params.mixture));
  static const auto kernel =
      detail::pick_variant(&weigh_block_generic, &weigh_block_avx2, &weigh_block_avx512);
  for (std::size_t first = 0; first < logw.size(); first += kBlock) {
    const std::size_t count = std::min(kBlock, logw.size() - first);
    kernel(plans, range_max, expected.data() + first * ranges.size(), params, logw.data() + first,
           count);
  }
}

}  // namespace mote
