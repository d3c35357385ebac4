// The likelihood-field gather, compiled per instruction set (likelihood_gather.hpp).
//
// GCC 12 emulates a vector gather with 16 scalar loads and inserts unless the target's tuning
// says gathers are fast, which made this loop 1.4 ns per particle-beam: the AVX2 and AVX-512
// variants are written with the gather intrinsic. Each variant's pose loop (fast_sin_cos) is
// vectorized by the compiler for that variant's instruction set.
#include "likelihood_gather.hpp"

#include "mote/core/isa_target.hpp"
#include "mote/engine/fast_math.hpp"

#if MOTE_ISA_DISPATCH
#include <immintrin.h>
#endif

// GCC 12 warns inside its own AVX-512 intrinsics (_mm512_undefined_ps in max/min/cvtt/gather)
// at -O3: a false positive (GCC bug 105593), fatal with MOTE_WERROR.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace mote::detail {
namespace {

// Particle poses in table cells for one block: endpoint (bx, by) lands on cell
// (col0 + c bx - s by, row0 + s bx + c by).
struct TablePoses {
  alignas(64) float col0[kLikelihoodBlock];
  alignas(64) float row0[kLikelihoodBlock];
  alignas(64) float c[kLikelihoodBlock];
  alignas(64) float s[kLikelihoodBlock];
};

// Position (col0, row0) and heading rotated by the map yaw and scaled to cells (c, s), so an
// endpoint costs 4 multiply-adds, 4 clamps and a gather.
MOTE_ALWAYS_INLINE void table_poses(const TableTransform& t, const ParticleView& particles,
                                    std::size_t begin, std::size_t lanes, TablePoses& p,
                                    float* sum) {
  for (std::size_t k = 0; k < lanes; ++k) {
    const float dx = particles.x[begin + k] - t.origin_x;
    const float dy = particles.y[begin + k] - t.origin_y;
    p.col0[k] = (t.cos_yaw * dx + t.sin_yaw * dy) * t.inv_resolution + t.border;
    p.row0[k] = (t.cos_yaw * dy - t.sin_yaw * dx) * t.inv_resolution + t.border;
    const SinCos sc = fast_sin_cos(particles.theta[begin + k]);
    p.c[k] = (sc.cos * t.cos_yaw + sc.sin * t.sin_yaw) * t.inv_resolution;
    p.s[k] = (sc.sin * t.cos_yaw - sc.cos * t.sin_yaw) * t.inv_resolution;
    sum[k] = 0.0F;
  }
}

// Lanes from k on, one at a time: the generic variant, and the tail that is not a whole vector.
MOTE_ALWAYS_INLINE void add_beam_scalar(const LikelihoodView& table, const TablePoses& p, float bx,
                                        float by, float* sum, std::size_t k, std::size_t count) {
  for (; k < count; ++k) {
    sum[k] +=
        table.at_cell(p.col0[k] + p.c[k] * bx - p.s[k] * by, p.row0[k] + p.s[k] * bx + p.c[k] * by);
  }
}

MOTE_TARGET_GENERIC void sums_generic(const LikelihoodView& table, const ParticleView& particles,
                                      std::size_t begin, std::size_t lanes, const Endpoints& e,
                                      float* sum) {
  TablePoses p;
  table_poses(table.transform, particles, begin, lanes, p, sum);
  for (std::size_t b = 0; b < e.count; ++b)
    add_beam_scalar(table, p, e.x[b], e.y[b], sum, 0, lanes);
}

#if MOTE_ISA_DISPATCH

MOTE_TARGET_AVX2 void add_beam_avx2(const LikelihoodView& table, const TablePoses& p, float bx,
                                    float by, float* sum, std::size_t count) {
  const TableTransform& t = table.transform;
  const __m256 vbx = _mm256_set1_ps(bx);
  const __m256 vby = _mm256_set1_ps(by);
  const __m256 zero = _mm256_setzero_ps();
  const __m256 max_col = _mm256_set1_ps(t.max_col);
  const __m256 max_row = _mm256_set1_ps(t.max_row);
  const __m256i stride = _mm256_set1_epi32(table.stride);
  std::size_t k = 0;
  for (; k + 8 <= count; k += 8) {
    const __m256 c = _mm256_load_ps(p.c + k);
    const __m256 s = _mm256_load_ps(p.s + k);
    __m256 col = _mm256_fnmadd_ps(s, vby, _mm256_fmadd_ps(c, vbx, _mm256_load_ps(p.col0 + k)));
    __m256 row = _mm256_fmadd_ps(c, vby, _mm256_fmadd_ps(s, vbx, _mm256_load_ps(p.row0 + k)));
    // max(x, 0) returns 0 for NaN (the second operand), as at_cell's `x > 0 ? x : 0` does.
    col = _mm256_min_ps(_mm256_max_ps(col, zero), max_col);
    row = _mm256_min_ps(_mm256_max_ps(row, zero), max_row);
    const __m256i index = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_cvttps_epi32(row), stride),
                                           _mm256_cvttps_epi32(col));
    const __m256 value = _mm256_i32gather_ps(table.data, index, 4);
    _mm256_store_ps(sum + k, _mm256_add_ps(_mm256_load_ps(sum + k), value));
  }
  add_beam_scalar(table, p, bx, by, sum, k, count);
}

MOTE_TARGET_AVX2 void sums_avx2(const LikelihoodView& table, const ParticleView& particles,
                                std::size_t begin, std::size_t lanes, const Endpoints& e,
                                float* sum) {
  TablePoses p;
  table_poses(table.transform, particles, begin, lanes, p, sum);
  for (std::size_t b = 0; b < e.count; ++b) add_beam_avx2(table, p, e.x[b], e.y[b], sum, lanes);
}

MOTE_TARGET_AVX512 void add_beam_avx512(const LikelihoodView& table, const TablePoses& p, float bx,
                                        float by, float* sum, std::size_t count) {
  const TableTransform& t = table.transform;
  const __m512 vbx = _mm512_set1_ps(bx);
  const __m512 vby = _mm512_set1_ps(by);
  const __m512 zero = _mm512_setzero_ps();
  const __m512 max_col = _mm512_set1_ps(t.max_col);
  const __m512 max_row = _mm512_set1_ps(t.max_row);
  const __m512i stride = _mm512_set1_epi32(table.stride);
  std::size_t k = 0;
  for (; k + 16 <= count; k += 16) {
    const __m512 c = _mm512_load_ps(p.c + k);
    const __m512 s = _mm512_load_ps(p.s + k);
    __m512 col = _mm512_fnmadd_ps(s, vby, _mm512_fmadd_ps(c, vbx, _mm512_load_ps(p.col0 + k)));
    __m512 row = _mm512_fmadd_ps(c, vby, _mm512_fmadd_ps(s, vbx, _mm512_load_ps(p.row0 + k)));
    col = _mm512_min_ps(_mm512_max_ps(col, zero), max_col);
    row = _mm512_min_ps(_mm512_max_ps(row, zero), max_row);
    const __m512i index = _mm512_add_epi32(_mm512_mullo_epi32(_mm512_cvttps_epi32(row), stride),
                                           _mm512_cvttps_epi32(col));
    const __m512 value = _mm512_i32gather_ps(index, table.data, 4);
    _mm512_store_ps(sum + k, _mm512_add_ps(_mm512_load_ps(sum + k), value));
  }
  add_beam_scalar(table, p, bx, by, sum, k, count);
}

MOTE_TARGET_AVX512 void sums_avx512(const LikelihoodView& table, const ParticleView& particles,
                                    std::size_t begin, std::size_t lanes, const Endpoints& e,
                                    float* sum) {
  TablePoses p;
  table_poses(table.transform, particles, begin, lanes, p, sum);
  for (std::size_t b = 0; b < e.count; ++b) {
    add_beam_avx512(table, p, e.x[b], e.y[b], sum, lanes);
  }
}

#else
#define sums_avx2 sums_generic
#define sums_avx512 sums_generic
#endif

}  // namespace

void likelihood_block_sums(const LikelihoodView& table, const ParticleView& particles,
                           std::size_t begin, std::size_t lanes, const Endpoints& endpoints,
                           float* sum) {
  static const auto kernel = pick_variant(&sums_generic, &sums_avx2, &sums_avx512);
  kernel(table, particles, begin, lanes, endpoints, sum);
}

}  // namespace mote::detail
