#pragma once
// The two reductions every log-weight computation needs, over a value v(i) computed on the fly:
// the maximum, and the sums of w_i = exp(v_i - shift) and of w_i^2. normalize() runs them on the
// stored log-weights, adaptive tempering on log-weights plus a tempered log-likelihood. Internal:
// not installed. The per-chunk loops are compiled per instruction set (isa_target.hpp).

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>

#include "mote/core/isa_target.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/fast_math.hpp"

namespace mote::detail {

inline constexpr float kNegInfF = -std::numeric_limits<float>::infinity();

// Floating-point sums use this fixed block size whatever the caller's grain, so the reduction
// tree, and with it every rounding, is the same for any grain as well as any thread count.
inline constexpr std::size_t kSumBlock = 2048;

struct WeightSums {
  double w = 0.0;
  double w_squared = 0.0;
};

template <class Value>
MOTE_ALWAYS_INLINE float max_chunk(std::size_t begin, std::size_t end, const Value& value_ref) {
  const Value value = value_ref;  // a local copy: its fields are loop invariants the loop can see
  std::array<float, par::kVectorWidth> lanes;  // per-lane maxima: vectorizes
  lanes.fill(kNegInfF);
  for (std::size_t i = begin; i < end; ++i) {
    float& m = lanes[i % par::kVectorWidth];
    m = std::max(m, value(i));  // std::max(m, NaN) keeps m: NaN ignored
  }
  return *std::max_element(lanes.begin(), lanes.end());
}

// Each sum runs in 16 fixed double lanes (lane = i mod 16, then lanes added in order): the
// grouping depends only on the indices, so vector and scalar code agree, and the lane loop
// vectorizes where a single accumulator could not.
template <class Value>
MOTE_ALWAYS_INLINE WeightSums sum_chunk(std::size_t begin, std::size_t end, float shift,
                                        const Value& value_ref) {
  const Value value = value_ref;  // as in max_chunk
  std::array<double, par::kVectorWidth> w{};
  std::array<double, par::kVectorWidth> w2{};
  const auto add = [&](std::size_t i, std::size_t lane) {
    const float v = value(i);
    const auto e = static_cast<double>(fast_exp((v == v ? v : kNegInfF) - shift));
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
}

// The variants of both chunk loops; Value is a caller's local type, so each instantiation stays
// in its translation unit.
template <class Value>
MOTE_TARGET_GENERIC float max_chunk_generic(std::size_t begin, std::size_t end,
                                            const Value& value) {
  return max_chunk(begin, end, value);
}
template <class Value>
MOTE_TARGET_AVX2 float max_chunk_avx2(std::size_t begin, std::size_t end, const Value& value) {
  return max_chunk(begin, end, value);
}
template <class Value>
MOTE_TARGET_AVX512 float max_chunk_avx512(std::size_t begin, std::size_t end, const Value& value) {
  return max_chunk(begin, end, value);
}
template <class Value>
MOTE_TARGET_GENERIC WeightSums sum_chunk_generic(std::size_t begin, std::size_t end, float shift,
                                                 const Value& value) {
  return sum_chunk(begin, end, shift, value);
}
template <class Value>
MOTE_TARGET_AVX2 WeightSums sum_chunk_avx2(std::size_t begin, std::size_t end, float shift,
                                           const Value& value) {
  return sum_chunk(begin, end, shift, value);
}
template <class Value>
MOTE_TARGET_AVX512 WeightSums sum_chunk_avx512(std::size_t begin, std::size_t end, float shift,
                                               const Value& value) {
  return sum_chunk(begin, end, shift, value);
}

/// max_i v(i), NaN ignored; -inf when every value is -inf or NaN.
template <class Value>
float max_value(std::size_t n, std::size_t grain, const Value& value) {
  static const auto kernel =
      pick_variant(&max_chunk_generic<Value>, &max_chunk_avx2<Value>, &max_chunk_avx512<Value>);
  return par::reduce(
      n, grain, kNegInfF,
      /*partial=*/[&](std::size_t begin, std::size_t end) { return kernel(begin, end, value); },
      /*join=*/[](float a, float b) { return std::max(a, b); });
}

/// Sums of w_i = exp(v(i) - shift) and of w_i^2 in one pass (NaN -> weight 0), over the fixed
/// blocks of kSumBlock.
template <class Value>
WeightSums sum_weights(std::size_t n, float shift, const Value& value) {
  static const auto kernel =
      pick_variant(&sum_chunk_generic<Value>, &sum_chunk_avx2<Value>, &sum_chunk_avx512<Value>);
  return par::reduce(
      n, kSumBlock, WeightSums{},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) { return kernel(begin, end, shift, value); },
      /*join=*/
      [](WeightSums a, WeightSums b) {
        return WeightSums{a.w + b.w, a.w_squared + b.w_squared};
      });
}

}  // namespace mote::detail
