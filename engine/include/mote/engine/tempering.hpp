#pragma once
/// \file
/// Adaptive likelihood tempering: the exponent tau of each scan's likelihood chosen per update
/// from the particles' own log-likelihoods, so that the weighted set keeps a target share of
/// its effective sample size. The beams of one scan are not independent (Thrun et al., section
/// 6.3.4), and the full product over them is overconfident by a factor that depends on the
/// sensor, the map and how far the filter is from the truth; a fixed exponent fitted to one log
/// does not carry over to another. Choosing tau so that the ESS falls to a fixed fraction of its
/// value before the scan is adaptive tempering as in sequential Monte Carlo (Jasra, Stephens,
/// Doucet and Tsagaris 2011, "Inference for Levy-driven stochastic volatility models via adaptive
/// sequential Monte Carlo", section 3; the annealed particle filter of Deutscher, Blake and Reid
/// 2000 chooses its annealing rates the same way).

#include <cstddef>

#include "mote/engine/chunks.hpp"
#include "mote/engine/particles.hpp"

namespace mote {

/// How the exponent is searched.
struct TemperingConfig {
  /// Target ESS(tau) / ESS(0): the share of the effective sample size one scan may consume.
  double target_ess_fraction = 0.1;
  /// Accept a trial whose ESS is within this share of the target ESS (the search's tolerance).
  double tolerance = 0.1;
  double min_tau = 1e-4;  ///< smallest exponent tried (a scan always counts a little)
  double max_tau = 1.0;   ///< largest: never sharper than the plain product of beams
  int max_trials = 24;    ///< bisection steps at most (log tau halves its interval each step)
};

/// The exponent chosen, and what the search saw.
struct TemperingChoice {
  double tau = 1.0;         ///< the exponent applied
  double ess_before = 0.0;  ///< ESS of the prior weights (tau = 0)
  double ess_after = 0.0;   ///< ESS with tau applied
  int trials = 0;           ///< ESS evaluations the search made
};

/// ESS = (sum w_i)^2 / sum w_i^2 of the weights w_i = exp(logw_i + tau * loglik_i) (NaN or -inf
/// terms weigh 0); 0 when every weight is 0. Sums run over a fixed block grid: bit-identical
/// for any thread count and grain.
[[nodiscard]] double tempered_ess(const float* logw, const float* loglik, std::size_t n, float tau,
                                  std::size_t grain = kDefaultGrain);

/// The largest tau in [min_tau, max_tau] with ESS(tau) >= target * ESS(0), to the tolerance:
/// max_tau when the scan cannot lower the ESS that far, min_tau when even that lowers it further.
/// ESS(tau) falls as tau grows for the likelihoods MCL meets; the search is a bisection on
/// log tau, so the result depends only on the inputs (deterministic).
[[nodiscard]] TemperingChoice choose_tempering(const float* logw, const float* loglik,
                                               std::size_t n, const TemperingConfig& config,
                                               std::size_t grain = kDefaultGrain);

/// logw_i += tau * loglik_i for i in [0, particles.size()), in the same float arithmetic that
/// tempered_ess evaluates.
void apply_tempering(const ParticleView& particles, const float* loglik, float tau,
                     std::size_t grain = kDefaultGrain);

}  // namespace mote
