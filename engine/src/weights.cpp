#include "mote/engine/weights.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "log_weights.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/fast_math.hpp"

namespace mote {
namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();

// Floating-point sums use this fixed block size whatever the caller's grain, so the reduction
// tree, and with it every rounding, is the same for any grain as well as any thread count.
constexpr std::size_t kSumBlock = 2048;

float max_log_weight(const float* logw, std::size_t n, std::size_t grain) {
  return par::reduce(
      n, grain, kNegInf,
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        std::array<float, par::kVectorWidth> lanes;  // per-lane maxima: vectorizes
        lanes.fill(kNegInf);
        for (std::size_t i = begin; i < end; ++i) {
          float& m = lanes[i % par::kVectorWidth];
          m = std::max(m, logw[i]);  // std::max(m, NaN) keeps m: NaN ignored
        }
        return *std::max_element(lanes.begin(), lanes.end());
      },
      /*join=*/[](float a, float b) { return std::max(a, b); });
}

// Sums of w_i = exp(logw_i - shift) and of w_i^2 in one pass (NaN -> weight 0): what
// normalization needs for the total and, through w_i / total, for the effective sample size.
// Each sum runs in 16 fixed double lanes (lane = i mod 16, then lanes added in order): the
// grouping depends only on the indices, so vector and scalar code agree, and the lane loop
// vectorizes where a single accumulator could not.
struct WeightSums {
  double w = 0.0;
  double w_squared = 0.0;
};

WeightSums sum_weights_and_squares(const float* logw, std::size_t n, float shift) {
  return par::reduce(
      n, kSumBlock, WeightSums{},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        std::array<double, par::kVectorWidth> w{};
        std::array<double, par::kVectorWidth> w2{};
        const auto add = [&](std::size_t i, std::size_t lane) {
          const float v = logw[i];
          const auto e = static_cast<double>(fast_exp((v == v ? v : kNegInf) - shift));
          w[lane] += e;
          w2[lane] += e * e;
        };
        std::size_t i = begin;
        for (; i + par::kVectorWidth <= end; i += par::kVectorWidth) {
          for (std::size_t k = 0; k < par::kVectorWidth; ++k) add(i + k, k);
        }
        for (std::size_t k = 0; i < end; ++i, ++k) add(i, k);
        WeightSums sums;
        for (std::size_t k = 0; k < par::kVectorWidth; ++k) {
          sums.w += w[k];
          sums.w_squared += w2[k];
        }
        return sums;
      },
      /*join=*/
      [](WeightSums a, WeightSums b) {
        return WeightSums{a.w + b.w, a.w_squared + b.w_squared};
      });
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
  const WeightSums sums = sum_weights_and_squares(logw, n, max_logw);
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
