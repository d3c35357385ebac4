#pragma once
// The likelihood-field inner loop: for one beam endpoint (bx, by) in the robot frame, add the
// table value under every particle's projected endpoint to sum[k] (engine-internal).
//
// GCC 12 with -mtune=generic (what -march=native gives on this Xeon) emulates a vector gather
// with 16 scalar loads and inserts, which made this loop 1.4 ns per particle-beam. With AVX-512
// or AVX2 enabled at compile time the loop is written with the hardware gather instead; other
// targets keep the portable loop. All variants compute the same formula (LikelihoodView::at_cell
// on col = col0 + c bx - s by, row = row0 + s bx + c by); the vector ones fuse the multiply-adds.

#include <cstddef>

#include "mote/maps/likelihood_table.hpp"

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

// GCC 12 warns inside its own AVX-512 intrinsics (_mm512_undefined_ps in max/min/cvtt/gather)
// at -O3: a false positive (GCC bug 105593), fatal with MOTE_WERROR.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace mote::detail {

// Particle poses in table cells for one block: endpoint (bx, by) lands on cell
// (col0 + c bx - s by, row0 + s bx + c by).
struct TablePoses {
  const float* col0;
  const float* row0;
  const float* c;
  const float* s;
};

// The arrays hold at least count floats and are 64-byte aligned; a count that is not a whole
// number of vectors ends with the portable loop.
inline void add_beam_likelihood(const LikelihoodView& table, const TablePoses& p, float bx,
                                float by, float* sum, std::size_t count) {
  const TableTransform& t = table.transform;
#if defined(__AVX512F__)
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
    // max(x, 0) returns 0 for NaN (the second operand), as at_cell's `x > 0 ? x : 0` does.
    col = _mm512_min_ps(_mm512_max_ps(col, zero), max_col);
    row = _mm512_min_ps(_mm512_max_ps(row, zero), max_row);
    const __m512i index = _mm512_add_epi32(_mm512_mullo_epi32(_mm512_cvttps_epi32(row), stride),
                                           _mm512_cvttps_epi32(col));
    const __m512 value = _mm512_i32gather_ps(index, table.data, 4);
    _mm512_store_ps(sum + k, _mm512_add_ps(_mm512_load_ps(sum + k), value));
  }
#elif defined(__AVX2__)
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
    col = _mm256_min_ps(_mm256_max_ps(col, zero), max_col);
    row = _mm256_min_ps(_mm256_max_ps(row, zero), max_row);
    const __m256i index = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_cvttps_epi32(row), stride),
                                           _mm256_cvttps_epi32(col));
    const __m256 value = _mm256_i32gather_ps(table.data, index, 4);
    _mm256_store_ps(sum + k, _mm256_add_ps(_mm256_load_ps(sum + k), value));
  }
#else
  std::size_t k = 0;
#endif
  (void)t;
  for (; k < count; ++k) {
    sum[k] +=
        table.at_cell(p.col0[k] + p.c[k] * bx - p.s[k] * by, p.row0[k] + p.s[k] * bx + p.c[k] * by);
  }
}

}  // namespace mote::detail

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
