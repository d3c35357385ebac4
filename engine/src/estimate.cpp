#include "mote/engine/estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "moments.hpp"
#include "mote/core/parallel.hpp"

namespace mote {
namespace {

// Moments are summed over a fixed block size, not the caller's grain, so the reduction tree
// (and every rounding) is the same for any grain and any thread count.
constexpr std::size_t kSumBlock = 2048;

float max_log_weight(const ConstParticleView& p, std::size_t grain) {
  constexpr float kNegInf = -std::numeric_limits<float>::infinity();
  return par::reduce(
      p.size(), grain, kNegInf,
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        float m = kNegInf;
        for (std::size_t i = begin; i < end; ++i) m = std::max(m, p.logw[i]);
        return m;
      },
      /*join=*/[](float a, float b) { return std::max(a, b); });
}

// Weight relative to the largest, so an unnormalized set does not overflow; NaN weighs 0.
double relative_weight(float logw, float max_logw) {
  return logw == logw ? std::exp(static_cast<double>(logw - max_logw)) : 0.0;
}

}  // namespace

PoseEstimate estimate(const ConstParticleView& p, std::size_t grain) {
  PoseEstimate out;
  const float max_logw = max_log_weight(p, grain);
  if (!std::isfinite(max_logw)) return out;
  const detail::FirstMoments first = par::reduce(
      p.size(), kSumBlock, detail::FirstMoments{},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        detail::FirstMoments m;
        for (std::size_t i = begin; i < end; ++i) {
          m.add(relative_weight(p.logw[i], max_logw), p.x[i], p.y[i], p.theta[i]);
        }
        return m;
      },
      /*join=*/[](const detail::FirstMoments& a, const detail::FirstMoments& b) { return a + b; });
  out.mean = first.mean();
  const detail::SecondMoments second = par::reduce(
      p.size(), kSumBlock, detail::SecondMoments{},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        detail::SecondMoments m;
        for (std::size_t i = begin; i < end; ++i) {
          m.add(relative_weight(p.logw[i], max_logw), out.mean, p.x[i], p.y[i], p.theta[i]);
        }
        return m;
      },
      /*join=*/
      [](const detail::SecondMoments& a, const detail::SecondMoments& b) { return a + b; });
  out.covariance = second.covariance(first.s[0]);
  out.weight = 1.0;
  out.count = p.size();
  return out;
}

const PoseEstimate* best_cluster(const std::vector<PoseEstimate>& clusters) noexcept {
  const auto it = std::max_element(
      clusters.begin(), clusters.end(),
      [](const PoseEstimate& a, const PoseEstimate& b) { return a.weight < b.weight; });
  return it == clusters.end() ? nullptr : &*it;
}

}  // namespace mote
