#include "mote/engine/weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "log_weights.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/fast_math.hpp"
#include "weight_sums.hpp"

namespace mote {
namespace {

constexpr float kNegInf = detail::kNegInfF;

float max_log_weight(const float* logw, std::size_t n, std::size_t grain) {
  return detail::max_value(n, grain, [logw](std::size_t i) { return logw[i]; });
}

detail::WeightSums sum_weights_and_squares(const float* logw, std::size_t n, float shift) {
  return detail::sum_weights(n, shift, [logw](std::size_t i) { return logw[i]; });
}

void fill_uniform(float* logw, std::size_t n, std::size_t grain) {
  const float uniform = -std::log(static_cast<float>(n));
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) {
    std::fill(logw + begin, logw + end, uniform);
  });
}

}  // namespace

namespace detail {

NormalizeResult normalize_log_weights(float* logw, std::size_t n, std::size_t grain) {
  NormalizeResult r;
  if (n == 0) return r;
  const float max_logw = max_log_weight(logw, n, grain);
  if (!std::isfinite(max_logw)) {  // all -inf / NaN, or a +inf weight: no usable information
    fill_uniform(logw, n, grain);
    constexpr double kNegInfD = -std::numeric_limits<double>::infinity();
    return {WeightStatus::kDegenerate, kNegInfD, kNegInfD, static_cast<double>(n)};
  }
  const detail::WeightSums sums = sum_weights_and_squares(logw, n, max_logw);
  const double total = sums.w;  // >= 1: the max contributes exp(0)
  const double log_total = static_cast<double>(max_logw) + std::log(total);
  // Subtract in two steps: v - max is exact for nearby values (Sterbenz), and log(total) is a
  // small number with full float precision; rounding log_total itself to float would scale
  // every weight by up to 1 +- 2^-24 |log_total| (3e-5 at log-weights near 1000).
  const auto log_sum = static_cast<float>(std::log(total));
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const float v = logw[i];
      logw[i] = v == v ? (v - max_logw) - log_sum : kNegInf;
    }
  });
  r.status = WeightStatus::kOk;
  r.log_total = log_total;
  r.log_mean_likelihood = log_total;  // see weights.hpp: w_avg when the priors summed to 1
  // 1 / sum of (w_i / total)^2 (Thrun section 4.3.4), from the same pass as the total.
  r.effective_sample_size = total * total / sums.w_squared;
  return r;
}

double log_weights_ess(const float* logw, std::size_t n) {
  if (n == 0) return 0.0;
  const double sum_sq = sum_weights_and_squares(logw, n, 0.0F).w_squared;  // sum of w_i^2
  return sum_sq > 0.0 ? 1.0 / sum_sq : static_cast<double>(n);
}

}  // namespace detail

NormalizeResult normalize(const ParticleView& p, std::size_t grain) {
  return detail::normalize_log_weights(p.logw, p.size(), grain);
}

double effective_sample_size(const ConstParticleView& p, std::size_t /*grain*/) {
  return detail::log_weights_ess(p.logw, p.size());
}

}  // namespace mote
