#pragma once
/// \file
/// Internal: confirmed range-table queries (RangeTableOptions::confirm). A table entry is a
/// claim: its lattice point's ray, at its table direction, enters a blocking cell after so
/// many cells. The claim names a wall face (the grid line nearest its hit point), and the
/// query's own ray crosses that line at an exact distance; where the map blocks just beyond the
/// crossing and is free just before it, the query's ray does enter a blocking cell there. So a
/// confirmed claim is an exact upper bound of the query's range, and the nearest confirmed claim
/// of several neighbours is its range unless every neighbour's ray misses a nearer obstacle.
/// Measured on Intel, Willow, Stata basement and Wean (BENCHMARKS.md, "Claims that name a
/// wall face").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "range_table_angles.hpp"
#include "range_table_claims.hpp"
#include "range_table_impl.hpp"
#include "range_table_sweep.hpp"

namespace mote {

namespace detail {

inline constexpr float kNotConfirmed = std::numeric_limits<float>::infinity();
/// A claimed hit this close (cells) to both grid lines lies at a corner: both faces are tried.
inline constexpr float kCornerSlack = 0.2F;

/// Whether cell (i, j) blocks, off-map cells free.
[[nodiscard]] inline bool blocks_at(const CellMask& m, int i, int j) noexcept {
  const bool on_map = (static_cast<unsigned>(i) < static_cast<unsigned>(m.width)) &&
                      (static_cast<unsigned>(j) < static_cast<unsigned>(m.height));
  const std::size_t at = on_map ? static_cast<std::size_t>(j) * static_cast<std::size_t>(m.width) +
                                      static_cast<std::size_t>(i)
                                : 0;
  return on_map && m.cells[at] != 0;
}

/// Round to the nearest integer for |v| < 2^22 (grid lines), without a libm call.
[[nodiscard]] inline float round_to_line(float v) noexcept {
  constexpr float kShift = 12582912.0F;  // 1.5 * 2^23: adding it leaves no fraction bits
  const float shifted = (v < 0.0F ? -v : v) + kShift;
  const float r = shifted - kShift;
  return v < 0.0F ? -r : r;
}

/// A query ray in cells: origin, unit direction and its reciprocal (infinite along an axis).
struct QueryRay {
  float ox = 0.0F;
  float oy = 0.0F;
  float ux = 1.0F;
  float uy = 0.0F;
  float inv_ux = 1.0F;
  float inv_uy = 0.0F;
};

/// The query ray from (ox, oy) along (ux, uy) (cells, unit) crosses grid line `line` (of x when
/// `vertical`, else of y) from a free cell into a blocking one: the crossing's distance (cells),
/// else kNotConfirmed. Off-map cells are free, as for the exact casters.
[[nodiscard]] inline float face_crossing(const CellMask& m, const QueryRay& q, bool vertical,
                                         float line) noexcept {
  const float ox = q.ox;
  const float oy = q.oy;
  const float ux = q.ux;
  const float uy = q.uy;
  const float toward = vertical ? ux : uy;
  const float t = (line - (vertical ? ox : oy)) * (vertical ? q.inv_ux : q.inv_uy);
  // Behind the sensor, parallel to the line (t infinite or NaN) or beyond any map.
  const bool ahead = t >= 0.0F && t < 1.0e6F;
  const float at = ahead ? t : 0.0F;
  const float across_f = vertical ? oy + at * uy : ox + at * ux;
  const auto truncated = static_cast<int>(across_f);
  const int across = truncated - (across_f < static_cast<float>(truncated) ? 1 : 0);  // floor
  const int l = static_cast<int>(line);
  const int beyond = toward > 0.0F ? l : l - 1;
  const int before = toward > 0.0F ? l - 1 : l;
  const bool enters = vertical ? blocks_at(m, beyond, across) && !blocks_at(m, before, across)
                               : blocks_at(m, across, beyond) && !blocks_at(m, across, before);
  return ahead && enters ? t : kNotConfirmed;
}

/// The nearest confirmed crossing of the face(s) a claimed hit point (hx, hy) (cells) names.
[[nodiscard]] inline float confirm_claim(const CellMask& m, const QueryRay& q, float hx,
                                         float hy) noexcept {
  const float fx = round_to_line(hx);
  const float fy = round_to_line(hy);
  const float ex = std::abs(hx - fx);
  const float ey = std::abs(hy - fy);
  // Both crossings, then the ones the claim names.
  const float tx = face_crossing(m, q, true, fx);
  const float ty = face_crossing(m, q, false, fy);
  const bool names_x = ex <= ey || ex < kCornerSlack;
  const bool names_y = ey < ex || ey < kCornerSlack;
  return std::min(names_x ? tx : kNotConfirmed, names_y ? ty : kNotConfirmed);
}

/// The candidates nearest the ray along table direction (dx, dy) on its left and on its right
/// (either may be missing: Candidates::kCount).
[[nodiscard]] inline std::array<std::size_t, 2> nearest_each_side(const Candidates& c, float dx,
                                                                  float dy) noexcept {
  std::array<std::size_t, 2> pick{Candidates::kCount, Candidates::kCount};
  std::array<float, 2> best{kNotConfirmed, kNotConfirmed};
  for (std::size_t k = 0; k < Candidates::kCount; ++k) {
    if (c.missing[k] != 0) continue;
    const float lateral = dx * c.wy[k] - dy * c.wx[k];
    const std::size_t side = lateral < 0.0F ? 1 : 0;
    if (std::abs(lateral) < best[side]) {
      best[side] = std::abs(lateral);
      pick[side] = k;
    }
  }
  return pick;
}

/// Candidate k's claim at table angle a on query ray q: its confirmed crossing (cells), else
/// kNotConfirmed; `every_claim_leaves` is cleared when the claim's ray met a wall.
[[nodiscard]] inline float check_claim(const ClaimTable& t, const Candidates& c, std::size_t k,
                                       std::size_t a, const QueryRay& q,
                                       bool& every_claim_leaves) noexcept {
  const std::uint16_t v = t.ranges[std::size_t{c.slot[k]} * t.angles + a] & kNoHit;
  if (v == kNoHit) return kNotConfirmed;
  every_claim_leaves = false;
  const float r = static_cast<float>(v) * t.inv_units;
  const float hx = (q.ox + c.wx[k]) + r * t.cos_a[a];
  const float hy = (q.oy + c.wy[k]) + r * t.sin_a[a];
  return confirm_claim(t.mask, q, hx, hy);
}

/// The query ray of a beam from (ox, oy) cells along unit (ux, uy).
[[nodiscard]] inline QueryRay query_ray(float ox, float oy, float ux, float uy) noexcept {
  return {ox, oy, ux, uy, 1.0F / ux, 1.0F / uy};
}

}  // namespace detail

template <class Direction>
void RangeTable::Impl::confirm_beams(const detail::Candidates& c, double gx, double gy,
                                     double heading, std::span<const double> beam_index,
                                     const Direction& dir, float max_range,
                                     detail::BeamScratch& scratch, float* out) const noexcept {
  const auto ox = static_cast<float>(gx / resolution);
  const auto oy = static_cast<float>(gy / resolution);
  const int n = options.angles;
  const std::size_t beams = beam_index.size();
  for (std::size_t b = 0; b < beams; ++b) {
    float frac = 0.0F;
    const std::size_t below = detail::angle_below(heading + beam_index[b], n, frac);
    scratch.angle[b] = static_cast<std::uint32_t>(below);
    scratch.next[b] = below + 1 == static_cast<std::size_t>(n) ? 0 : scratch.angle[b] + 1;
    const auto [ux, uy] = dir(b);
    scratch.dx[b] = ux;
    scratch.dy[b] = uy;
  }
  const detail::ClaimTable t{ranges,
                             static_cast<std::uint32_t>(n),
                             cos_a.data(),
                             sin_a.data(),
                             static_cast<float>(1.0 / stats.units_per_cell),
                             mask(),
                             cell_bits.get()};
  // First the nearest neighbour on each side of the ray at both directions around it (on
  // vector lanes where the CPU has them)...
  detail::four_claims(t, c, ox, oy,
                      {{scratch.angle.data(), beams},
                       {scratch.next.data(), beams},
                       {scratch.dx.data(), beams},
                       {scratch.dy.data(), beams},
                       {scratch.nearest.data(), beams},
                       {scratch.leaves.data(), beams}},
                      claims_on_lanes);
  for (std::size_t b = 0; b < beams; ++b) {
    float nearest = scratch.nearest[b];
    bool every_claim_leaves = scratch.leaves[b] != 0;
    // ... and when none confirms (1.6 % of Intel tracking's beams), every neighbour at both.
    if (nearest == detail::kNotConfirmed && !every_claim_leaves) {
      const detail::QueryRay q = detail::query_ray(ox, oy, scratch.dx[b], scratch.dy[b]);
      for (const std::uint32_t a : {scratch.angle[b], scratch.next[b]}) {
        for (std::size_t k = 0; k < detail::Candidates::kCount; ++k) {
          if (c.missing[k] != 0) continue;
          nearest = std::min(nearest, detail::check_claim(t, c, k, a, q, every_claim_leaves));
        }
      }
    }
    if (nearest != detail::kNotConfirmed) {
      out[b] = std::clamp(nearest * resolution, 0.0F, max_range);
    } else {
      // Every claim leaves the map: so does the ray, as the plain table reads it.
      out[b] = every_claim_leaves ? max_range : detail::kCastExactly;
    }
  }
}

}  // namespace mote
