#include "mote/engine/resample.hpp"

#include <algorithm>
#include <cmath>

#include "mote/core/parallel.hpp"
#include "mote/engine/fast_math.hpp"
#include "mote/engine/philox.hpp"

namespace mote {
namespace {

constexpr std::uint64_t kOne = std::uint64_t{1} << 32;  // one copy in 32.32 fixed point

// The shared front end of every scheme: the exclusive prefix sum C of q_i = floor(w_i n_out
// 2^32) in scratch 1, with C[N] = total; q_i = C[i+1] - C[i]. q is computed inside the scan,
// so no q column is written or read back. Weights must be normalized; q_i <= n_out 2^32 < 2^64.
struct FixedWeights {
  const std::uint64_t* c;
  std::uint64_t total;
  [[nodiscard]] std::uint64_t q(std::size_t i) const { return c[i + 1] - c[i]; }
};

FixedWeights fixed_point_weights(ParticleStore& store, std::size_t n_out, std::size_t grain) {
  const ConstParticleView in = store.view();
  std::uint64_t* c = store.scratch(1);
  const double scale = static_cast<double>(n_out) * static_cast<double>(kOne);
  const std::uint64_t total =
      par::exclusive_scan<std::uint64_t>(in.size(), grain, c, [&](std::size_t i) {
        return static_cast<std::uint64_t>(static_cast<double>(fast_exp(in.logw[i])) * scale);
      });
  c[in.size()] = total;
  return {c, total};
}

// The scheme's own fixed-point total may differ from n_out * 2^32 by a few units; a position
// at or past the total belongs to the last particle with positive weight.
std::size_t ancestor_of(const FixedWeights& fw, std::size_t n, std::uint64_t pos) {
  pos = std::min(pos, fw.total - 1);
  return static_cast<std::size_t>(std::upper_bound(fw.c, fw.c + n, pos) - fw.c) - 1;
}

void copy_particle(const ConstParticleView& in, std::size_t i, const ParticleView& out,
                   std::size_t j) {
  out.x[j] = in.x[i];
  out.y[j] = in.y[i];
  out.theta[j] = in.theta[i];
}

// Writes uniform weights into the gathered buffer and makes it current.
void finish(ParticleStore& store, std::size_t n_out) {
  store.swap_buffers(n_out);
  store.set_uniform_weights();
}

std::uint64_t comb_offset(std::uint64_t seed, std::uint64_t step) {
  const RngStream rng{seed, step, RngPurpose::kResample};
  return rng.block(0)[0];  // U in [0, 2^32): the one uniform of systematic resampling
}

// Fallback when every q_i rounded to 0 (not normalized, or n_out == 0): spread evenly.
bool resample_empty_total(ParticleStore& store, std::size_t n_out, const FixedWeights& fw) {
  if (fw.total != 0 && n_out != 0) return false;
  const ConstParticleView in = store.view();
  const ParticleView out = store.spare(n_out);
  for (std::size_t j = 0; j < n_out && in.size() > 0; ++j) {
    copy_particle(in, j * in.size() / n_out, out, j);
  }
  finish(store, n_out);
  return true;
}

// Comb tooth j sits at j 2^32 + u; past the total it belongs to the last weighted particle.
std::uint64_t tooth(std::size_t j, std::uint64_t u, const FixedWeights& fw) {
  return std::min(j * kOne + u, fw.total - 1);
}

}  // namespace

void resample_systematic(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, grain);
  if (resample_empty_total(store, n_out, fw)) return;
  const std::uint64_t u = comb_offset(seed, step);
  const ConstParticleView in = store.view();
  const ParticleView out = store.spare(n_out);
  // Parallel over chunks of outputs: each chunk finds the ancestor of its first tooth by binary
  // search (the largest i with C_i <= tooth), then walks the pointer like the serial sampler.
  // Both give the same i for every tooth, so the result is the serial one exactly.
  par::for_each_chunk(n_out, grain, [&](std::size_t begin, std::size_t end) {
    std::size_t i = ancestor_of(fw, in.size(), tooth(begin, u, fw));
    for (std::size_t j = begin; j < end; ++j) {
      const std::uint64_t pos = tooth(j, u, fw);
      while (fw.c[i + 1] <= pos) ++i;
      copy_particle(in, i, out, j);
    }
  });
  finish(store, n_out);
}

void resample_systematic_serial(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                                std::uint64_t step) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, store.size() + 1);
  if (resample_empty_total(store, n_out, fw)) return;
  const std::uint64_t u = comb_offset(seed, step);
  const ConstParticleView in = store.view();
  const ParticleView out = store.spare(n_out);
  std::size_t i = 0;
  for (std::size_t j = 0; j < n_out; ++j) {
    const std::uint64_t pos = std::min(j * kOne + u, fw.total - 1);  // the comb tooth
    while (fw.c[i + 1] <= pos) ++i;  // Thrun table 4.4, lines 7-9 (c[N] = total > pos)
    copy_particle(in, i, out, j);
  }
  finish(store, n_out);
}

namespace {

// Output j copies the particle whose fixed-point interval holds position(fw, j); the shared
// body of the independent-draw baselines (multinomial, stratified).
template <class Position>
void resample_by_position(ParticleStore& store, std::size_t n_out, std::size_t grain,
                          const Position& position) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, grain);
  if (resample_empty_total(store, n_out, fw)) return;
  const ConstParticleView in = store.view();
  const ParticleView out = store.spare(n_out);
  par::for_each_chunk(n_out, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j) {
      copy_particle(in, ancestor_of(fw, in.size(), position(fw, j)), out, j);
    }
  });
  finish(store, n_out);
}

}  // namespace

void resample_multinomial(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                          std::uint64_t step, std::size_t grain) {
  const RngStream rng{seed, step, RngPurpose::kResample};
  resample_by_position(store, n_out, grain, [&](const FixedWeights& fw, std::size_t j) {
    const double uj = rng.uniform_double(static_cast<std::uint32_t>(j), 1);
    return static_cast<std::uint64_t>(uj * static_cast<double>(fw.total));
  });
}

void resample_stratified(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain) {
  const RngStream rng{seed, step, RngPurpose::kResample};
  resample_by_position(store, n_out, grain, [&](const FixedWeights&, std::size_t j) {
    return j * kOne + rng.block(static_cast<std::uint32_t>(j), 2)[0];
  });
}

void resample_residual(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                       std::uint64_t step) {
  store.reserve(n_out);
  const FixedWeights fw = fixed_point_weights(store, n_out, store.size() + 1);
  if (resample_empty_total(store, n_out, fw)) return;
  const ConstParticleView in = store.view();
  const ParticleView out = store.spare(n_out);
  std::size_t j = 0;
  std::uint64_t residual_total = 0;
  std::uint64_t* residual = store.scratch(0);  // residual prefix sums beside C
  for (std::size_t i = 0; i < in.size(); ++i) {
    for (std::uint64_t k = 0; k < (fw.q(i) >> 32) && j < n_out; ++k) copy_particle(in, i, out, j++);
    residual[i] = residual_total;
    residual_total += fw.q(i) & (kOne - 1);
  }
  residual[in.size()] = residual_total;
  const FixedWeights rest{residual, residual_total};
  const RngStream rng{seed, step, RngPurpose::kResample};
  for (; j < n_out; ++j) {
    const double uj = rng.uniform_double(static_cast<std::uint32_t>(j), 3);
    const auto pos = static_cast<std::uint64_t>(uj * static_cast<double>(residual_total));
    copy_particle(in, residual_total == 0 ? in.size() - 1 : ancestor_of(rest, in.size(), pos), out,
                  j);
  }
  finish(store, n_out);
}

}  // namespace mote
