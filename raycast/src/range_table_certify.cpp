#include "range_table_certify.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "mote/core/parallel.hpp"
#include "range_table_sweep.hpp"

namespace mote::detail {

namespace {

/// A no-hit entry as a range (cells): far beyond any hit, and two of them agree exactly.
constexpr float kFar = 1.0e9F;
constexpr std::size_t kSlotGrain = 256;
/// Neighbours farther than this (lattice steps) beside the ray are outside every query's tube.
constexpr float kReach = 1.05F;

/// A lattice neighbour of a slot: its offset (cells) and its slot.
struct Neighbour {
  float wx = 0.0F;
  float wy = 0.0F;
  std::uint32_t slot = 0;
};

/// Per-task rows: a slot's ranges (cells), a neighbour's, and the per-angle verdict.
struct Rows {
  explicit Rows(std::size_t angles) : own(angles), other(angles), bad(angles) {}
  std::vector<float> own;
  std::vector<float> other;
  std::vector<std::uint8_t> bad;
};

void decode(const std::uint16_t* row, std::size_t angles, float inv_units, float* out) {
  for (std::size_t k = 0; k < angles; ++k) {
    const auto v = static_cast<std::uint16_t>(row[k] & kNoHit);
    out[k] = v == kNoHit ? kFar : static_cast<float>(v) * inv_units;
  }
}

/// The lattice neighbours of slot p that hold a point (up to 8).
std::vector<Neighbour> neighbours_of(const CertifyInput& in, std::uint32_t p) {
  const TableLayout& t = in.layout;
  const auto cell = t.cell_of_slot[p];
  const int bi = static_cast<int>(cell % static_cast<std::uint32_t>(t.width)) / t.lattice;
  const int bj = static_cast<int>(cell / static_cast<std::uint32_t>(t.width)) / t.lattice;
  std::vector<Neighbour> out;
  for (int nj = std::max(bj - 1, 0); nj <= std::min(bj + 1, t.blocks_h - 1); ++nj) {
    for (int ni = std::max(bi - 1, 0); ni <= std::min(bi + 1, t.blocks_w - 1); ++ni) {
      const std::uint32_t q =
          t.slot_of_block[static_cast<std::size_t>(nj) * static_cast<std::size_t>(t.blocks_w) +
                          static_cast<std::size_t>(ni)];
      if (q == kNoSlot || q == p) continue;
      out.push_back({in.point_x[q] - in.point_x[p], in.point_y[q] - in.point_y[p], q});
    }
  }
  return out;
}

/// Interval k (from angle k to k + 1, where a query interpolates) is bad when the second
/// difference of the ranges at k or at k + 1 exceeds tol: a jump (a corner, a gap) between
/// neighbouring directions, which linear interpolation would smear, rather than the smooth
/// change of a slanted wall, which it follows.
void check_angles(const float* r, std::size_t n, float tol, std::uint8_t* bad) {
  for (std::size_t k = 0; k < n; ++k) {
    const float prev = r[k == 0 ? n - 1 : k - 1];
    const float next = r[k + 1 == n ? 0 : k + 1];
    const float next2 = r[k + 2 >= n ? k + 2 - n : k + 2];
    bad[k] = static_cast<std::uint8_t>(std::abs(prev - 2.0F * r[k] + next) > tol ||
                                       std::abs(r[k] - 2.0F * next + next2) > tol);
  }
}

/// How a neighbour at one offset (cells) from a point compares with it, per angle: its offset
/// along the ray and the disagreement allowed, infinite when it is out of every query's tube.
/// On a lattice of every cell the offsets repeat (8 of them), so tasks keep them.
struct OffsetRow {
  float wx = 0.0F;
  float wy = 0.0F;
  std::vector<float> along;
  std::vector<float> allowed;
};

/// Angle k is bad when neighbour w, within kReach lattice steps of p's ray, hits farther from
/// p's hit (along the ray) than a planar wall allows: a query's origin lies at most half a step
/// beside the ray, so a wall seen slanted by w moves the query's hit by at most half a step's
/// share of w's disagreement; anything more is a corner or gap inside the query's tube.
OffsetRow offset_row(const CertifyInput& in, float wx, float wy, float tol) {
  const std::size_t n = in.cos_a.size();
  const auto lattice = static_cast<float>(in.layout.lattice);
  OffsetRow row{wx, wy, std::vector<float>(n), std::vector<float>(n)};
  for (std::size_t k = 0; k < n; ++k) {
    const float c = in.cos_a[k];
    const float s = in.sin_a[k];
    const float lateral = std::abs(c * wy - s * wx);
    row.along[k] = c * wx + s * wy;
    row.allowed[k] = lateral <= kReach * lattice ? tol * std::max(1.0F, lateral / (0.5F * lattice))
                                                 : std::numeric_limits<float>::infinity();
  }
  return row;
}

/// The row of offset (wx, wy) from a task's cache (filled on first use, at most kCached rows).
const OffsetRow& row_for(std::vector<OffsetRow>& cache, const CertifyInput& in, float wx, float wy,
                         float tol, OffsetRow& spare) {
  for (const OffsetRow& r : cache) {
    if (r.wx == wx && r.wy == wy) return r;
  }
  constexpr std::size_t kCached = 64;
  if (cache.size() < kCached) return cache.emplace_back(offset_row(in, wx, wy, tol));
  spare = offset_row(in, wx, wy, tol);
  return spare;
}

void check_neighbour(const OffsetRow& w, const float* own, const float* other, std::size_t n,
                     std::uint8_t* bad) {
  for (std::size_t k = 0; k < n; ++k) {
    bad[k] |= static_cast<std::uint8_t>(std::abs(w.along[k] + other[k] - own[k]) > w.allowed[k]);
  }
}

}  // namespace

std::size_t certify(const CertifyInput& in, std::span<std::uint16_t> ranges) {
  const std::size_t n = in.cos_a.size();
  const std::size_t points = in.layout.points();
  const auto inv_units = static_cast<float>(1.0 / in.units_per_cell);
  const auto tol = static_cast<float>(in.tolerance_cells);
  // Verdicts first, one bit per entry in their own array (words of 32 angles: a row is whole
  // words), so that no task reads a row another task is marking.
  const std::size_t words = n / 32;
  std::vector<std::uint32_t> verdict(points * words);
  par::for_each_chunk(points, kSlotGrain, [&](std::size_t begin, std::size_t end) {
    Rows rows(n);
    std::vector<OffsetRow> cache;
    OffsetRow spare;
    for (std::size_t p = begin; p < end; ++p) {
      decode(ranges.data() + p * n, n, inv_units, rows.own.data());
      check_angles(rows.own.data(), n, tol, rows.bad.data());
      for (const Neighbour& w : neighbours_of(in, static_cast<std::uint32_t>(p))) {
        decode(ranges.data() + std::size_t{w.slot} * n, n, inv_units, rows.other.data());
        const OffsetRow& offset = row_for(cache, in, w.wx, w.wy, tol, spare);
        check_neighbour(offset, rows.own.data(), rows.other.data(), n, rows.bad.data());
      }
      for (std::size_t k = 0; k < n; ++k) {
        verdict[p * words + k / 32] |= std::uint32_t{rows.bad[k]} << (k % 32);
      }
    }
  });
  std::atomic<std::size_t> marked{0};  // a sum of integers: the same for any thread count
  par::for_each_chunk(points, kSlotGrain, [&](std::size_t begin, std::size_t end) {
    std::size_t count = 0;
    for (std::size_t e = begin * n; e < end * n; ++e) {
      if (((verdict[e / 32] >> (e % 32)) & 1U) != 0) {
        ranges[e] = static_cast<std::uint16_t>(ranges[e] | kUncertified);
        ++count;
      }
    }
    marked.fetch_add(count, std::memory_order_relaxed);
  });
  return marked.load();
}

}  // namespace mote::detail
