#include "mote/engine/tempering.hpp"

#include <cmath>

#include "mote/core/parallel.hpp"
#include "weight_sums.hpp"

namespace mote {
namespace {

// logw_i + tau * loglik_i, the one formula both the search and apply_tempering use.
struct Tempered {
  const float* logw;
  const float* loglik;
  float tau;
  // At tau = 0 the prior itself, even where the log-likelihood is -inf (0 * -inf is NaN).
  float operator()(std::size_t i) const {
    return tau == 0.0F ? logw[i] : logw[i] + tau * loglik[i];
  }
};

}  // namespace

double tempered_ess(const float* logw, const float* loglik, std::size_t n, float tau,
                    std::size_t grain) {
  const Tempered value{logw, loglik, tau};
  const float shift = detail::max_value(n, grain, value);
  if (!std::isfinite(shift)) return 0.0;
  const detail::WeightSums sums = detail::sum_weights(n, shift, value);
  return sums.w * sums.w / sums.w_squared;  // w_squared >= 1: the maximum weighs exp(0)
}

TemperingChoice choose_tempering(const float* logw, const float* loglik, std::size_t n,
                                 const TemperingConfig& config, std::size_t grain) {
  TemperingChoice choice;
  const auto ess = [&](double tau) {
    ++choice.trials;
    return tempered_ess(logw, loglik, n, static_cast<float>(tau), grain);
  };
  choice.ess_before = ess(0.0);
  const double target = config.target_ess_fraction * choice.ess_before;
  const double slack = config.tolerance * target;
  const auto accept = [&](double tau, double e) {
    choice.tau = tau;
    choice.ess_after = e;
    return choice;
  };
  if (const double e = ess(config.max_tau); e >= target - slack) return accept(config.max_tau, e);
  const double ess_min_tau = ess(config.min_tau);
  if (ess_min_tau <= target + slack) return accept(config.min_tau, ess_min_tau);
  // Invariant: ESS(lo) > target > ESS(hi); bisect in log tau, since the exponent that fits
  // spans decades (0.5 for a sparse scan near the truth, 1e-3 for a dense one far from it).
  double lo = std::log(config.min_tau);
  double hi = std::log(config.max_tau);
  double best_tau = config.min_tau;
  double best_ess = ess_min_tau;
  while (choice.trials < config.max_trials + 3) {
    const double mid = 0.5 * (lo + hi);
    const double tau = std::exp(mid);
    const double e = ess(tau);
    if (std::abs(e - target) <= slack) return accept(tau, e);
    if (e > target) {
      lo = mid;
      best_tau = tau;  // the largest tau seen that keeps the ESS above the target
      best_ess = e;
    } else {
      hi = mid;
    }
  }
  return accept(best_tau, best_ess);
}

void apply_tempering(const ParticleView& p, const float* loglik, float tau, std::size_t grain) {
  const Tempered value{p.logw, loglik, tau};
  par::for_each_chunk(p.size(), grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) p.logw[i] = value(i);
  });
}

}  // namespace mote
