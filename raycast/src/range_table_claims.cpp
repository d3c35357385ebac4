// The confirmed table's four claims a beam, scalar and on AVX-512 lanes (range_table_claims.hpp).
// Compiled with -ffp-contract=off (raycast/CMakeLists.txt): both variants then round every
// product and sum alike, so they give the same ranges bit for bit.
#include "range_table_claims.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "mote/core/isa_target.hpp"
#include "range_table_confirm.hpp"

#if MOTE_ISA_DISPATCH
#include <immintrin.h>
#endif

namespace mote::detail {

CellBits::CellBits(const CellMask& m) {
  const auto w = static_cast<std::size_t>(m.width);
  const auto h = static_cast<std::size_t>(m.height);
  const std::size_t words = (w * h + 31) / 32 + 1;  // the spare word: see the class
  rows_.assign(words, 0);
  columns_.assign(words, 0);
  for (std::size_t j = 0; j < h; ++j) {
    for (std::size_t i = 0; i < w; ++i) {
      if (m.cells[j * w + i] == 0) continue;
      rows_[(j * w + i) / 32] |= std::uint32_t{1} << ((j * w + i) % 32);
      columns_[(i * h + j) / 32] |= std::uint32_t{1} << ((i * h + j) % 32);
    }
  }
}

bool claims_fit_lanes(std::size_t entries, int angles, int width, int height) noexcept {
  constexpr std::size_t kIndexLimit = std::size_t{1} << 31;  // 32-bit signed gather indices
  return angles % 2 == 0 && entries / 2 < kIndexLimit &&
         static_cast<std::size_t>(width) * static_cast<std::size_t>(height) < kIndexLimit;
}

void four_claims_scalar(const ClaimTable& t, const Candidates& c, float ox, float oy,
                        const ClaimBeams& beams) noexcept {
  for (std::size_t b = 0; b < beams.ux.size(); ++b) {
    const QueryRay q = query_ray(ox, oy, beams.ux[b], beams.uy[b]);
    float nearest = kNotConfirmed;
    bool every_claim_leaves = true;
    for (const std::uint32_t a : {beams.below[b], beams.next[b]}) {
      for (const std::size_t k : nearest_each_side(c, t.cos_a[a], t.sin_a[a])) {
        if (k == Candidates::kCount) continue;
        nearest = std::min(nearest, check_claim(t, c, k, a, q, every_claim_leaves));
      }
    }
    beams.nearest[b] = nearest;
    beams.leaves[b] = every_claim_leaves ? 1 : 0;
  }
}

#if MOTE_ISA_DISPATCH

namespace {

#define MOTE_LANES __attribute__((target("avx512f,avx512dq,avx512bw,avx512vl,avx2,fma")))

/// One query ray per lane (cells): origin, unit direction and its reciprocal.
struct LaneRays {
  __m512 ox, oy, ux, uy, inv_ux, inv_uy;
};

/// Which of the two cells on either side of a face block, per lane: cells (k - 1, across) and
/// (k, across) along a row (`along_rows`), else (across, k - 1) and (across, k) along a
/// column; off-map cells are free (blocks_at). `low` gets the first cell's, the result is the
/// second's. One gather: both bits lie in the 32 bits from the byte holding the first on-map one.
MOTE_LANES inline __mmask16 lanes_pair_blocks(const ClaimTable& t, __mmask16 live, bool along_rows,
                                              __m512i k, __m512i across, __mmask16& low) noexcept {
  const int length = along_rows ? t.mask.width : t.mask.height;  // cells along k
  const int lines = along_rows ? t.mask.height : t.mask.width;   // rows (columns) across
  const __m512i one = _mm512_set1_epi32(1);
  const __m512i k_low = _mm512_sub_epi32(k, one);
  const __mmask16 line_on = _mm512_mask_cmplt_epu32_mask(live, across, _mm512_set1_epi32(lines));
  const __mmask16 low_on = _mm512_mask_cmplt_epu32_mask(line_on, k_low, _mm512_set1_epi32(length));
  const __mmask16 high_on = _mm512_mask_cmplt_epu32_mask(line_on, k, _mm512_set1_epi32(length));
  const __m512i at_low =
      _mm512_add_epi32(_mm512_mullo_epi32(across, _mm512_set1_epi32(length)), k_low);
  // The byte of the first on-map cell of the pair: the low one, else the high one.
  const __m512i first_on = _mm512_mask_mov_epi32(_mm512_add_epi32(at_low, one), low_on, at_low);
  const __m512i byte = _mm512_srli_epi32(first_on, 3);
  const __m512i word = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), low_on | high_on, byte,
                                                   t.bits->bits(along_rows), 1);
  // Low's bit (-1, read as no bit, when low is off the map and high starts a byte).
  const __m512i offset = _mm512_sub_epi32(at_low, _mm512_slli_epi32(byte, 3));
  low = _mm512_mask_test_epi32_mask(low_on, _mm512_srlv_epi32(word, offset), one);
  return _mm512_mask_test_epi32_mask(high_on,
                                     _mm512_srlv_epi32(word, _mm512_add_epi32(offset, one)), one);
}

/// face_crossing on lanes: where each lane's ray crosses grid line `line` (of x when
/// `vertical`) from a free cell into a blocking one, else kNotConfirmed.
MOTE_LANES inline __m512 lanes_face(const ClaimTable& t, __mmask16 live, const LaneRays& q,
                                    bool vertical, __m512 line) noexcept {
  const __m512 o = vertical ? q.ox : q.oy;
  const __m512 o_across = vertical ? q.oy : q.ox;
  const __m512 toward = vertical ? q.ux : q.uy;
  const __m512 u_across = vertical ? q.uy : q.ux;
  const __m512 t_line = _mm512_mul_ps(_mm512_sub_ps(line, o), vertical ? q.inv_ux : q.inv_uy);
  const __mmask16 ahead = _mm512_cmp_ps_mask(t_line, _mm512_setzero_ps(), _CMP_GE_OQ) &
                          _mm512_cmp_ps_mask(t_line, _mm512_set1_ps(1.0e6F), _CMP_LT_OQ);
  const __m512 at = _mm512_maskz_mov_ps(ahead, t_line);
  const __m512 across_f = _mm512_add_ps(o_across, _mm512_mul_ps(at, u_across));
  const __m512i truncated = _mm512_cvttps_epi32(across_f);
  const __mmask16 below = _mm512_cmp_ps_mask(across_f, _mm512_cvtepi32_ps(truncated), _CMP_LT_OQ);
  const __m512i across = _mm512_mask_sub_epi32(truncated, below, truncated, _mm512_set1_epi32(1));
  // The cells before and beyond the line: k - 1 and k travelling forward, k and k - 1 back.
  __mmask16 low = 0;
  const __mmask16 high =
      lanes_pair_blocks(t, live & ahead, vertical, _mm512_cvttps_epi32(line), across, low);
  const __mmask16 forward = _mm512_cmp_ps_mask(toward, _mm512_setzero_ps(), _CMP_GT_OQ);
  const __mmask16 enters = (forward & high & ~low) | (~forward & low & ~high);
  return _mm512_mask_mov_ps(_mm512_set1_ps(kNotConfirmed), ahead & enters, t_line);
}

/// confirm_claim on lanes, for claimed hit points (hx, hy) cells.
MOTE_LANES inline __m512 lanes_claim(const ClaimTable& t, __mmask16 live, const LaneRays& q,
                                     __m512 hx, __m512 hy) noexcept {
  constexpr int kNearest = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
  const __m512 fx = _mm512_roundscale_ps(hx, kNearest);
  const __m512 fy = _mm512_roundscale_ps(hy, kNearest);
  const __m512 ex = _mm512_abs_ps(_mm512_sub_ps(hx, fx));
  const __m512 ey = _mm512_abs_ps(_mm512_sub_ps(hy, fy));
  const __m512 tx = lanes_face(t, live, q, true, fx);
  const __m512 ty = lanes_face(t, live, q, false, fy);
  const __m512 slack = _mm512_set1_ps(kCornerSlack);
  const __mmask16 names_x =
      _mm512_cmp_ps_mask(ex, ey, _CMP_LE_OQ) | _mm512_cmp_ps_mask(ex, slack, _CMP_LT_OQ);
  const __mmask16 names_y =
      _mm512_cmp_ps_mask(ey, ex, _CMP_LT_OQ) | _mm512_cmp_ps_mask(ey, slack, _CMP_LT_OQ);
  const __m512 none = _mm512_set1_ps(kNotConfirmed);
  return _mm512_min_ps(_mm512_mask_mov_ps(none, names_x, tx),
                       _mm512_mask_mov_ps(none, names_y, ty));
}

/// The candidate nearest each lane's table direction on one side of it (nearest_each_side).
struct LanePick {
  __mmask16 found = 0;
  __m512 lateral;
  __m512i slot;
  __m512 wx, wy;
};

/// check_claim on lanes for the picked candidates at table angle `a` (lanes' indices): folds
/// the confirmed crossings into `nearest` and marks in `claimed` the lanes whose claim met a wall.
MOTE_LANES inline void lanes_check(const ClaimTable& t, const LaneRays& q, const LanePick& pick,
                                   __m512i a, __m512 cos_a, __m512 sin_a, __m512& nearest,
                                   __mmask16& claimed) noexcept {
  const __m512i entry =
      _mm512_add_epi32(_mm512_mullo_epi32(pick.slot, _mm512_set1_epi32(int(t.angles))), a);
  // The 32-bit word holding the 16-bit entry (always inside the table: angles is even).
  const __m512i word = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), pick.found,
                                                   _mm512_srli_epi32(entry, 1), t.ranges, 4);
  const __m512i shift = _mm512_slli_epi32(_mm512_and_si512(entry, _mm512_set1_epi32(1)), 4);
  const __m512i v =
      _mm512_and_si512(_mm512_srlv_epi32(word, shift), _mm512_set1_epi32(int{kNoHit}));
  const __mmask16 hit = _mm512_mask_cmpneq_epi32_mask(pick.found, v, _mm512_set1_epi32(kNoHit));
  claimed |= hit;
  const __m512 r = _mm512_mul_ps(_mm512_cvtepi32_ps(v), _mm512_set1_ps(t.inv_units));
  const __m512 hx = _mm512_add_ps(_mm512_add_ps(q.ox, pick.wx), _mm512_mul_ps(r, cos_a));
  const __m512 hy = _mm512_add_ps(_mm512_add_ps(q.oy, pick.wy), _mm512_mul_ps(r, sin_a));
  nearest = _mm512_mask_min_ps(nearest, hit, nearest, lanes_claim(t, hit, q, hx, hy));
}

/// The four claims of 16 beams (fewer in `live`) from b0 on.
MOTE_LANES void claims_16(const ClaimTable& t, const Candidates& c, const LaneRays& q,
                          __mmask16 live, const ClaimBeams& beams, std::size_t b0) noexcept {
  __m512 nearest = _mm512_set1_ps(kNotConfirmed);
  __mmask16 claimed = 0;
  for (const std::uint32_t* angles : {beams.below.data(), beams.next.data()}) {
    const __m512i a = _mm512_maskz_loadu_epi32(live, angles + b0);
    const __m512 cos_a = _mm512_i32gather_ps(a, t.cos_a, 4);
    const __m512 sin_a = _mm512_i32gather_ps(a, t.sin_a, 4);
    // nearest_each_side: side 0 (left, lateral >= 0) and side 1; the first nearest wins.
    std::array<LanePick, 2> picks;
    for (LanePick& p : picks) {
      p.lateral = _mm512_set1_ps(kNotConfirmed);
      p.slot = _mm512_setzero_si512();
      p.wx = p.wy = _mm512_setzero_ps();
    }
    for (std::size_t k = 0; k < Candidates::kCount; ++k) {
      if (c.missing[k] != 0) continue;
      const __m512 wx = _mm512_set1_ps(c.wx[k]);
      const __m512 wy = _mm512_set1_ps(c.wy[k]);
      const __m512 lateral = _mm512_sub_ps(_mm512_mul_ps(cos_a, wy), _mm512_mul_ps(sin_a, wx));
      const __m512 distance = _mm512_abs_ps(lateral);
      const __mmask16 right = _mm512_cmp_ps_mask(lateral, _mm512_setzero_ps(), _CMP_LT_OQ);
      for (std::size_t side = 0; side < 2; ++side) {
        LanePick& p = picks[side];
        const __mmask16 on_side = side == 0 ? __mmask16(~right) : right;
        const __mmask16 nearer =
            _mm512_mask_cmp_ps_mask(on_side & live, distance, p.lateral, _CMP_LT_OQ);
        p.found |= nearer;
        p.lateral = _mm512_mask_mov_ps(p.lateral, nearer, distance);
        p.slot = _mm512_mask_mov_epi32(p.slot, nearer, _mm512_set1_epi32(int(c.slot[k])));
        p.wx = _mm512_mask_mov_ps(p.wx, nearer, wx);
        p.wy = _mm512_mask_mov_ps(p.wy, nearer, wy);
      }
    }
    for (const LanePick& p : picks) lanes_check(t, q, p, a, cos_a, sin_a, nearest, claimed);
  }
  _mm512_mask_storeu_ps(beams.nearest.data() + b0, live, nearest);
  _mm512_mask_storeu_epi32(beams.leaves.data() + b0, live,
                           _mm512_maskz_mov_epi32(__mmask16(~claimed), _mm512_set1_epi32(1)));
}

MOTE_LANES void four_claims_avx512(const ClaimTable& t, const Candidates& c, float ox, float oy,
                                   const ClaimBeams& beams) noexcept {
  const std::size_t count = beams.ux.size();
  for (std::size_t b0 = 0; b0 < count; b0 += 16) {
    const std::size_t left = count - b0;
    const auto live = static_cast<__mmask16>(left >= 16 ? 0xFFFFU : (1U << left) - 1U);
    LaneRays q;
    q.ox = _mm512_set1_ps(ox);
    q.oy = _mm512_set1_ps(oy);
    q.ux = _mm512_maskz_loadu_ps(live, beams.ux.data() + b0);
    q.uy = _mm512_maskz_loadu_ps(live, beams.uy.data() + b0);
    q.inv_ux = _mm512_div_ps(_mm512_set1_ps(1.0F), q.ux);
    q.inv_uy = _mm512_div_ps(_mm512_set1_ps(1.0F), q.uy);
    claims_16(t, c, q, live, beams, b0);
  }
}

#undef MOTE_LANES

}  // namespace

bool four_claims_lanes(const ClaimTable& t, const Candidates& c, float ox, float oy,
                       const ClaimBeams& beams) noexcept {
  if (best_supported_isa() != Isa::kAvx512 || t.bits == nullptr) return false;
  four_claims_avx512(t, c, ox, oy, beams);
  return true;
}

#else

bool four_claims_lanes(const ClaimTable&, const Candidates&, float, float,
                       const ClaimBeams&) noexcept {
  return false;
}

#endif

void four_claims(const ClaimTable& t, const Candidates& c, float ox, float oy,
                 const ClaimBeams& beams, bool lanes) noexcept {
  if (lanes && active_isa() == Isa::kAvx512 && four_claims_lanes(t, c, ox, oy, beams)) return;
  four_claims_scalar(t, c, ox, oy, beams);
}

}  // namespace mote::detail
