#pragma once
/// \file
/// Importance weights in the log domain: reweighting by a measurement log-likelihood (with
/// tempering), normalization by log-sum-exp over the deterministic reduction tree, the effective
/// sample size and the mean likelihood that augmented MCL needs (Thrun table 8.3).

#include <cstddef>
#include <type_traits>

#include "mote/engine/chunks.hpp"
#include "mote/engine/particles.hpp"

namespace mote {

/// Adds log-likelihoods chunk by chunk: chunk_fn(particles, begin, end) must add
/// log p(z | x_i) (already tempered if it wishes) to particles.logw[i] for i in [begin, end),
/// touching nothing outside its chunk. This is the hook sensor models build on.
template <class ChunkFn>
requires std::is_invocable_v<const ChunkFn&, const ParticleView&, std::size_t, std::size_t>
void reweight_chunks(const ParticleView& particles, const ChunkFn& chunk_fn,
                     std::size_t grain = kDefaultGrain) {
  for_each_particle_chunk(particles.size(), grain, [&](std::size_t begin, std::size_t end) {
    chunk_fn(particles, begin, end);
  });
}

/// logw_i += tau * loglik(x_i, y_i, theta_i) for every particle; tau in (0, 1] is the tempering
/// exponent (likelihood raised to tau; amcl's laser models use tau = 1).
template <class LogLik>
requires std::is_invocable_r_v<double, const LogLik&, float, float, float>
void reweight(const ParticleView& particles, const LogLik& loglik, double tau = 1.0,
              std::size_t grain = kDefaultGrain) {
  reweight_chunks(
      particles,
      [&](const ParticleView& p, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          p.logw[i] += static_cast<float>(tau * loglik(p.x[i], p.y[i], p.theta[i]));
        }
      },
      grain);
}

/// Outcome of normalize.
enum class WeightStatus {
  kOk,          ///< weights normalized
  kDegenerate,  ///< every log-weight was -inf or NaN: weights were reset to uniform
  kEmpty,       ///< no particles
};

/// What normalize found, all computed before normalizing.
struct NormalizeResult {
  WeightStatus status = WeightStatus::kEmpty;
  /// log of the sum of exp(logw); -inf when degenerate.
  double log_total = 0.0;
  /// log of the prior-weighted mean likelihood, log sum_i w_prev,i p(z | x_i): the w_avg of
  /// augmented MCL (Thrun table 8.3, line 8), provided logw held log w_prev + log p(z | x) with
  /// sum w_prev = 1 (as after normalize, resample_systematic or initialize_*). It is then equal to
  /// log_total; with uniform priors 1/N it is log of the plain mean (1/N) sum_i p(z | x_i). For
  /// unnormalized priors it is off by log sum w_prev. -inf when degenerate.
  double log_mean_likelihood = 0.0;
  /// Effective sample size 1 / sum(w_i^2) of the normalized weights, in [1, N]; N when degenerate.
  double effective_sample_size = 0.0;

  [[nodiscard]] bool ok() const noexcept { return status == WeightStatus::kOk; }
};

/// Normalizes the log-weights so that sum exp(logw) = 1: subtracts max(logw) before
/// exponentiating, sums in double over the deterministic reduction tree, then subtracts
/// log(sum). NaN log-weights count as -inf (weight 0) and are overwritten with -inf. When no
/// particle has a finite log-weight, never produces NaN: sets every weight to 1/N and returns
/// kDegenerate, so the caller can reject the update or inject recovery particles. grain sets
/// the chunk size of the element-wise passes; sums run over a fixed block grid, so results are
/// bit-identical for any grain and thread count.
NormalizeResult normalize(const ParticleView& particles, std::size_t grain = kDefaultGrain);

/// 1 / sum(w_i^2) of already normalized log-weights (N for uniform weights, 1 for a point mass).
[[nodiscard]] double effective_sample_size(const ConstParticleView& particles,
                                           std::size_t grain = kDefaultGrain);

/// The resampling policy: true when ess < fraction * N (amcl-style selective resampling).
[[nodiscard]] inline bool should_resample(double ess, std::size_t n,
                                          double fraction = 0.5) noexcept {
  return fraction >= 1.0 || ess < fraction * static_cast<double>(n);
}

}  // namespace mote
