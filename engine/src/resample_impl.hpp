#pragma once
// The resampling schemes of resample.hpp as templates over the store they gather, so the pose
// ParticleStore (resample.cpp) and the generic StateStore (state_store.cpp) share one body per
// scheme. Internal: not installed. A store adapter S provides
//   reserve(n)            room for n particles in both buffers
//   size()                particles in the current buffer
//   log_weights()         the current, normalized log-weight column
//   scratch(k)            integer scratch column k (k = 0, 1) of capacity + 1 entries
//   gather(n_out)         a callable g(i, j) copying current state i into spare slot j
//   commit(n_out)         make the spare buffer current with n_out uniform weights

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "mote/core/parallel.hpp"
#include "mote/engine/philox.hpp"

namespace mote::detail {

inline constexpr std::uint64_t kOne = std::uint64_t{1} << 32;  // one copy in 32.32 fixed point

// The shared front end of every scheme: the exclusive prefix sum C of q_i = floor(w_i n_out
// 2^32) in scratch 1, with C[N] = total; q_i = C[i+1] - C[i]. q is computed inside the scan,
// so no q column is written or read back. Weights must be normalized; q_i <= n_out 2^32 < 2^64.
struct FixedWeights {
  const std::uint64_t* c;
  std::uint64_t total;
  [[nodiscard]] std::uint64_t q(std::size_t i) const { return c[i + 1] - c[i]; }
};

// out[i] = floor(exp(logw[i]) * scale) for i in [begin, end): the fixed-point weights, compiled
// per instruction set (fixed_point.cpp).
void fixed_point_block(const float* logw, double scale, std::uint64_t* out, std::size_t begin,
                       std::size_t end);

template <class S>
FixedWeights fixed_point_weights(S& store, std::size_t n_out, std::size_t grain) {
  const float* logw = store.log_weights();
  const std::size_t n = store.size();
  std::uint64_t* c = store.scratch(1);
  const double scale = static_cast<double>(n_out) * static_cast<double>(kOne);
  const std::uint64_t total = par::exclusive_scan_filled<std::uint64_t>(
      n, grain, c, [&](std::size_t begin, std::size_t end, std::uint64_t* out) {
        fixed_point_block(logw, scale, out, begin, end);
      });
  c[n] = total;
  return {c, total};
}

// The scheme's own fixed-point total may differ from n_out * 2^32 by a few units; a position
// at or past the total belongs to the last particle with positive weight.
inline std::size_t ancestor_of(const FixedWeights& fw, std::size_t n, std::uint64_t pos) {
  pos = std::min(pos, fw.total - 1);
  return static_cast<std::size_t>(std::upper_bound(fw.c, fw.c + n, pos) - fw.c) - 1;
}

inline std::uint64_t comb_offset(std::uint64_t seed, std::uint64_t step) {
  const RngStream rng{seed, step, RngPurpose::kResample};
  return rng.block(0)[0];  // U in [0, 2^32): the one uniform of systematic resampling
}

// Comb tooth j sits at j 2^32 + u; past the total it belongs to the last weighted particle.
inline std::uint64_t tooth(std::size_t j, std::uint64_t u, const FixedWeights& fw) {
  return std::min(j * kOne + u, fw.total - 1);
}

// Fallback when every q_i rounded to 0 (not normalized, or n_out == 0): spread evenly.
template <class S>
bool resample_empty_total(S& store, std::size_t n_out, const FixedWeights& fw) {
  if (fw.total != 0 && n_out != 0) return false;
  const std::size_t n = store.size();
  const auto gather = store.gather(n_out);
  for (std::size_t j = 0; j < n_out && n > 0; ++j) gather(j * n / n_out, j);
  store.commit(n_out);
  return true;
}

// The first comb tooth at or past C: tooth j (position min(j 2^32 + u, total - 1)) reaches C
// exactly when j 2^32 + u >= C, as long as C < total; no tooth reaches C >= total. Output j
// copies the largest i whose first tooth is at or before j, which is the serial sampler's i.
inline std::size_t first_tooth(std::uint64_t c, std::uint64_t u, const FixedWeights& fw,
                               std::size_t n_out) {
  if (c >= fw.total) return n_out;
  const std::uint64_t ahead = c > u ? c - u : 0;
  return std::min<std::size_t>(n_out, static_cast<std::size_t>((ahead + kOne - 1) >> 32));
}

// Copies between this many and none are written without a data-dependent branch: the serial
// sampler's inner loop stops after a random number of steps and mispredicted about once per
// particle.
inline constexpr std::size_t kUnrolledCopies = 4;

template <class S>
void systematic(S& store, std::size_t n_out, std::uint64_t seed, std::uint64_t step,
                std::size_t grain) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, grain);
  if (resample_empty_total(store, n_out, fw)) return;
  const std::uint64_t u = comb_offset(seed, step);
  const std::size_t n = store.size();
  const auto gather = store.gather(n_out);
  // Parallel over chunks of ancestors: particle i fills outputs [first_tooth(C_i),
  // first_tooth(C_{i+1})), so a chunk's outputs are known from its two ends and chunks never
  // share an output. Usually all kUnrolledCopies slots from the first are written, and the
  // surplus is overwritten by the following particles of the same chunk.
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) {
    const auto copy = gather;  // a local copy: its column pointers stay in registers
    std::size_t j = first_tooth(fw.c[begin], u, fw, n_out);
    const std::size_t j_end = first_tooth(fw.c[end], u, fw, n_out);
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t next = first_tooth(fw.c[i + 1], u, fw, n_out);
      if (next - j <= kUnrolledCopies && j + kUnrolledCopies <= j_end) {
        for (std::size_t k = 0; k < kUnrolledCopies; ++k) copy(i, j + k);
      } else {
        for (std::size_t k = j; k < next; ++k) copy(i, k);
      }
      j = next;
    }
  });
  store.commit(n_out);
}

template <class S>
void systematic_serial(S& store, std::size_t n_out, std::uint64_t seed, std::uint64_t step) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, store.size() + 1);
  if (resample_empty_total(store, n_out, fw)) return;
  const std::uint64_t u = comb_offset(seed, step);
  const auto gather = store.gather(n_out);
  std::size_t i = 0;
  for (std::size_t j = 0; j < n_out; ++j) {
    const std::uint64_t pos = tooth(j, u, fw);
    while (fw.c[i + 1] <= pos) ++i;  // Thrun table 4.4, lines 7-9 (c[N] = total > pos)
    gather(i, j);
  }
  store.commit(n_out);
}

// Output j copies the particle whose fixed-point interval holds position(fw, j); the shared
// body of the independent-draw baselines (multinomial, stratified).
template <class S, class Position>
void by_position(S& store, std::size_t n_out, std::size_t grain, const Position& position) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, grain);
  if (resample_empty_total(store, n_out, fw)) return;
  const std::size_t n = store.size();
  const auto gather = store.gather(n_out);
  par::for_each_chunk(n_out, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j) gather(ancestor_of(fw, n, position(fw, j)), j);
  });
  store.commit(n_out);
}

template <class S>
void multinomial(S& store, std::size_t n_out, std::uint64_t seed, std::uint64_t step,
                 std::size_t grain) {
  const RngStream rng{seed, step, RngPurpose::kResample};
  by_position(store, n_out, grain, [&](const FixedWeights& fw, std::size_t j) {
    const double uj = rng.uniform_double(static_cast<std::uint32_t>(j), 1);
    return static_cast<std::uint64_t>(uj * static_cast<double>(fw.total));
  });
}

template <class S>
void stratified(S& store, std::size_t n_out, std::uint64_t seed, std::uint64_t step,
                std::size_t grain) {
  const RngStream rng{seed, step, RngPurpose::kResample};
  by_position(store, n_out, grain, [&](const FixedWeights&, std::size_t j) {
    return j * kOne + rng.block(static_cast<std::uint32_t>(j), 2)[0];
  });
}

template <class S>
void residual(S& store, std::size_t n_out, std::uint64_t seed, std::uint64_t step) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, store.size() + 1);
  if (resample_empty_total(store, n_out, fw)) return;
  const std::size_t n = store.size();
  const auto gather = store.gather(n_out);
  std::size_t j = 0;
  std::uint64_t residual_total = 0;
  std::uint64_t* rest_c = store.scratch(0);  // residual prefix sums beside C
  for (std::size_t i = 0; i < n; ++i) {
    for (std::uint64_t k = 0; k < (fw.q(i) >> 32) && j < n_out; ++k) gather(i, j++);
    rest_c[i] = residual_total;
    residual_total += fw.q(i) & (kOne - 1);
  }
  rest_c[n] = residual_total;
  const FixedWeights rest{rest_c, residual_total};
  const RngStream rng{seed, step, RngPurpose::kResample};
  for (; j < n_out; ++j) {
    const double uj = rng.uniform_double(static_cast<std::uint32_t>(j), 3);
    const auto pos = static_cast<std::uint64_t>(uj * static_cast<double>(residual_total));
    gather(residual_total == 0 ? n - 1 : ancestor_of(rest, n, pos), j);
  }
  store.commit(n_out);
}

}  // namespace mote::detail
