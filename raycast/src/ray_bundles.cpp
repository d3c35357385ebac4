#include "ray_bundles.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

#include "grid_walk.hpp"
#include "mote/core/parallel.hpp"

namespace mote::detail {

namespace {

/// Cells along the bundle's major axis per strip: each strip's blocking cells are tested
/// against the rays still open, and a ray that hits in a strip is done after it.
constexpr int kStripCells = 8;
constexpr float kNoHit = std::numeric_limits<float>::infinity();
/// Stands for 1 / 0 along an axis the ray does not move on: (line - origin) times it is huge
/// unless the ray runs on the line itself, where it is 0 (the ray touches the cell: a hit, as
/// the grid walk stops where a wall touches a ray along a grid line). An infinity would give NaN.
constexpr float kParallel = 1.0e30F;
/// Slack (cells) on the bounds that pick a box's rays: float rounding of keys and slopes.
constexpr float kKeySlack = 1.0e-3F;
/// Beams per task of cast_bundles.
constexpr std::size_t kBundleBeams = 15;

/// How far (cells) past a box's corner a ray may pass and still be decided exactly
/// (reach_past_corner): the walls' reach, kSnapDistance, plus what float cells may be off by on
/// this map (a few units in the last place of its largest coordinate).
float near_window(const CellMask& m) {
  const auto largest = static_cast<double>(std::max(m.width, m.height));
  return static_cast<float>(kSnapDistance / static_cast<double>(m.resolution) +
                            8.0 * std::numeric_limits<float>::epsilon() * largest);
}

/// The bundle's wedge along its major axis (x when `along_x`), travelling toward `sign`:
/// origins' major coordinates within [m0, m1] (cells), the minor coordinate changing by
/// slope_lo .. slope_hi per cell of major coordinate; keys are minor coordinates at `ref`.
struct Wedge {
  bool along_x = true;
  int sign = 1;
  float m0 = 0.0F, m1 = 0.0F, slope_lo = 0.0F, slope_hi = 0.0F, ref = 0.0F;
};

/// The wedge of the group's rays, or false when they do not all travel the same way along one
/// axis (never within one heading bin; such rays are walked one by one).
bool wedge_of(const BundleScratch& s, std::size_t n, Wedge& w) {
  float sx = 0.0F;
  float sy = 0.0F;
  for (std::size_t k = 0; k < n; ++k) {
    sx += s.dx[k];
    sy += s.dy[k];
  }
  w.along_x = std::abs(sx) >= std::abs(sy);
  w.sign = (w.along_x ? sx : sy) >= 0.0F ? 1 : -1;
  const float* major_u = w.along_x ? s.dx.data() : s.dy.data();
  const float* minor_u = w.along_x ? s.dy.data() : s.dx.data();
  float travel = kNoHit;
  w.slope_lo = kNoHit;
  w.slope_hi = -kNoHit;
  for (std::size_t k = 0; k < n; ++k) {
    travel = std::min(travel, major_u[k] * static_cast<float>(w.sign));
    w.slope_lo = std::min(w.slope_lo, minor_u[k] / major_u[k]);
    w.slope_hi = std::max(w.slope_hi, minor_u[k] / major_u[k]);
  }
  // Steeper than 3:1 along the minor axis: not a bundle these strips can cut.
  if (!(travel > 0.3F)) return false;
  const std::vector<float>& major_o = w.along_x ? s.ox : s.oy;
  const auto [m0, m1] = std::minmax_element(major_o.begin(), major_o.begin() + std::ptrdiff_t(n));
  w.m0 = *m0;
  w.m1 = *m1;
  w.ref = 0.5F * (w.m0 + w.m1);
  return true;
}

/// Puts the rays in buckets of key, where each crosses the major line `ref` (extended behind
/// its origin), one bucket per cell (a counting sort), and fills the open arrays in that order.
/// Within a strip rays keep that order up to how much their slopes differ, which bounds the
/// buckets whose rays can reach a box.
void load_buckets(const Wedge& w, std::size_t n, float window, BundleScratch& s) {
  const float* major_o = w.along_x ? s.ox.data() : s.oy.data();
  const float* minor_o = w.along_x ? s.oy.data() : s.ox.data();
  const float* major_u = w.along_x ? s.dx.data() : s.dy.data();
  const float* minor_u = w.along_x ? s.dy.data() : s.dx.data();
  float low = kNoHit;
  float high = -kNoHit;
  for (std::size_t k = 0; k < n; ++k) {
    s.key[k] = minor_o[k] + minor_u[k] / major_u[k] * (w.ref - major_o[k]);
    low = std::min(low, s.key[k]);
    high = std::max(high, s.key[k]);
  }
  s.key_origin = std::floor(low);
  s.key_top = high;
  std::uint32_t buckets = 1;
  for (std::size_t k = 0; k < n; ++k) {
    s.bucket[k] = static_cast<std::uint32_t>(s.key[k] - s.key_origin);
    buckets = std::max(buckets, s.bucket[k] + 1);
  }
  s.starts.assign(buckets + 1, 0);
  for (std::size_t k = 0; k < n; ++k) ++s.starts[s.bucket[k] + 1];
  std::partial_sum(s.starts.begin(), s.starts.end(), s.starts.begin());
  s.fill.assign(s.starts.begin(), s.starts.end() - 1);
  for (std::size_t k = 0; k < n; ++k)
    s.order[s.fill[s.bucket[k]]++] = static_cast<std::uint32_t>(k);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t r = s.order[k];
    s.px[k] = s.ox[r];
    s.py[k] = s.oy[r];
    s.ix[k] = s.dx[r];  // reciprocals below, on vector lanes
    s.iy[k] = s.dy[r];
    s.ray_of[k] = r;
  }
  for (std::size_t k = 0; k < n; ++k) {
    // Both divisions, then the choice: no branch, so vector lanes (x / 0 is inf, not a trap).
    const float rx = 1.0F / s.ix[k];
    const float ry = 1.0F / s.iy[k];
    s.ix[k] = s.ix[k] != 0.0F ? rx : kParallel;
    s.iy[k] = s.iy[k] != 0.0F ? ry : kParallel;
    s.wx[k] = std::abs(window * s.ix[k]);
    s.wy[k] = std::abs(window * s.iy[k]);
    s.best[k] = kNoHit;
  }
}

/// Where the run of blocking cells of line `line` that holds cell `at` begins: cells are read
/// backward 64 at a time until a free one.
int run_start(const BitMask& bits, bool along_x, int line, int at) {
  while (at > 0) {
    const int from = std::max(0, at - 64);
    const int cells = at - from;
    const int ones = std::countl_one(bits.bits(along_x, line, from) << (64 - cells));
    at -= std::min(ones, cells);
    if (ones < cells) break;
  }
  return at;
}

/// One past where the run of blocking cells of line `line` that holds cell `at` ends (a zero
/// word closes every line).
int run_end(const BitMask& bits, bool along_x, int line, int at) {
  for (;;) {
    const int ones = std::countr_one(bits.bits(along_x, line, at));
    at += ones;
    if (ones < 64) return at;
  }
}

/// The runs of blocking cells across major cells [lo, hi] that reach minor cells [jlo, jhi], as
/// boxes. Each run is whole, also where it goes on past the window or past a 64-cell read: a
/// box's faces are then the map's, the same whichever bundle finds it (a run cut at a window's
/// edge would have a face, and a wall's reach past it, that the map does not).
void collect_boxes(const BitMask& bits, const Wedge& w, int lo, int hi, int jlo, int jhi,
                   std::vector<BundleScratch::Box>& boxes) {
  boxes.clear();
  for (int c = lo; c <= hi; ++c) {
    int j = jlo;
    while (j <= jhi) {
      const std::uint64_t word = bits.bits(w.along_x, c, j);
      if (word == 0) {
        j += 64;
        continue;
      }
      const int at = j + std::countr_zero(word);
      if (at > jhi) break;
      const int start = at == jlo ? run_start(bits, w.along_x, c, at) : at;
      const int end = run_end(bits, w.along_x, c, at);
      const auto major0 = static_cast<float>(c);
      const auto minor0 = static_cast<float>(start);
      const auto minor1 = static_cast<float>(end);
      boxes.push_back(w.along_x ? BundleScratch::Box{major0, major0 + 1.0F, minor0, minor1}
                                : BundleScratch::Box{minor0, minor1, major0, major0 + 1.0F});
      j = end;  // a free cell, or past the line's end
    }
  }
}

/// Where open ray k, when it misses the box by a hair, crosses one of its faces' lines within
/// kSnapDistance past the face's end, else kNoHit (cells): the exact casters' walls reach that
/// far past their ends, so such a ray stops there. In metres and doubles on the ray as traced,
/// as the grid walk decides it: a hair here is below float precision in cells.
float reach_past_corner(const CellMask& m, const BundleScratch& s, const BundleScratch::Box& box,
                        std::size_t k) {
  const float enter =
      std::max(std::min((box.x0 - s.px[k]) * s.ix[k], (box.x1 - s.px[k]) * s.ix[k]),
               std::min((box.y0 - s.py[k]) * s.iy[k], (box.y1 - s.py[k]) * s.iy[k]));
  const float leave =
      std::min(std::max((box.x0 - s.px[k]) * s.ix[k], (box.x1 - s.px[k]) * s.ix[k]),
               std::max((box.y0 - s.py[k]) * s.iy[k], (box.y1 - s.py[k]) * s.iy[k]));
  if (enter <= leave || enter - leave > s.wx[k] + s.wy[k]) return kNoHit;
  const std::uint32_t r = s.ray_of[k];
  const double ox = s.qx[r];
  const double oy = s.qy[r];
  const double dx = s.qdx[r];
  const double dy = s.qdy[r];
  const double x0 = m.line(static_cast<int>(box.x0));
  const double x1 = m.line(static_cast<int>(box.x1));
  const double y0 = m.line(static_cast<int>(box.y0));
  const double y1 = m.line(static_cast<int>(box.y1));
  double best = kNoHit;
  // The line `at` of one axis, crossed where the other coordinate lies within [lo, hi] widened.
  const auto cross = [&](double at, double o, double d, double o_other, double d_other, double lo,
                         double hi) {
    if (d == 0.0) return;
    const double t = (at - o) / d;
    const double along = o_other + t * d_other;
    if (t >= 0.0 && along >= lo - kSnapDistance && along <= hi + kSnapDistance) {
      best = std::min(best, t);
    }
  };
  for (const double x : {x0, x1}) cross(x, ox, dx, oy, dy, y0, y1);
  for (const double y : {y0, y1}) cross(y, oy, dy, ox, dx, x0, x1);
  return best == kNoHit ? kNoHit : static_cast<float>(best / static_cast<double>(m.resolution));
}

/// Rays [k0, k1)'s nearest entry into the box so far (slab test; cells along the ray), then
/// the few rays that miss it by less than a wall's reach, exactly.
void hit_box(const CellMask& m, BundleScratch& s, const BundleScratch::Box& box, std::size_t k0,
             std::size_t k1) {
  const float* __restrict px = s.px.data();
  const float* __restrict py = s.py.data();
  const float* __restrict ix = s.ix.data();
  const float* __restrict iy = s.iy.data();
  const float* __restrict wx = s.wx.data();
  const float* __restrict wy = s.wy.data();
  float* __restrict best = s.best.data();
  std::uint32_t near_misses = 0;
  // No dependence between rays and no branch: vector lanes.
  for (std::size_t k = k0; k < k1; ++k) {
    const float tx0 = (box.x0 - px[k]) * ix[k];
    const float tx1 = (box.x1 - px[k]) * ix[k];
    const float ty0 = (box.y0 - py[k]) * iy[k];
    const float ty1 = (box.y1 - py[k]) * iy[k];
    const float enter = std::max(std::min(tx0, tx1), std::min(ty0, ty1));
    const float leave = std::min(std::max(tx0, tx1), std::max(ty0, ty1));
    const float t = std::max(enter, 0.0F);  // a box behind the ray leaves before 0
    best[k] = std::min(best[k], t <= leave ? t : kNoHit);
    // Written with bitwise operators on integers, as these forms keep the loop on vector lanes.
    const std::uint32_t missed = enter > leave ? 1U : 0U;
    near_misses |= missed & (enter - leave <= wx[k] + wy[k] ? 1U : 0U);
  }
  if (near_misses == 0) return;
  for (std::size_t k = k0; k < k1; ++k) {
    best[k] = std::min(best[k], reach_past_corner(m, s, box, k));
  }
}

/// Each open ray's nearest entry into the strip's boxes. A box across [a0, a1] (minor) in
/// major cell [c, c + 1] is reached only by rays whose key lies in [a0, a1] moved back by what
/// their slope can add between `ref` and the box: a contiguous run of buckets.
void hit_boxes(const CellMask& m, const Wedge& w, float window, BundleScratch& s) {
  const auto buckets = static_cast<float>(s.starts.size() - 1);
  for (const BundleScratch::Box& box : s.boxes) {
    // minor(x) - key = slope * (x - ref) for x across the box's major extent.
    const float x0 = (w.along_x ? box.x0 : box.y0) - w.ref;
    const float x1 = (w.along_x ? box.x1 : box.y1) - w.ref;
    const float a = w.slope_lo * x0;
    const float b = w.slope_lo * x1;
    const float c = w.slope_hi * x0;
    const float d = w.slope_hi * x1;
    const float drift_lo = std::min(std::min(a, b), std::min(c, d));
    const float drift_hi = std::max(std::max(a, b), std::max(c, d));
    const float across0 = (w.along_x ? box.y0 : box.x0) - window;
    const float across1 = (w.along_x ? box.y1 : box.x1) + window;
    // Buckets [first, end), cut to the ones there are.
    const float first = std::floor(across0 - drift_hi - kKeySlack - s.key_origin);
    const float end = std::floor(across1 - drift_lo + kKeySlack - s.key_origin) + 1.0F;
    if (end <= 0.0F || first >= buckets) continue;
    hit_box(m, s, box, s.starts[static_cast<std::size_t>(std::max(first, 0.0F))],
            s.starts[static_cast<std::size_t>(std::min(end, buckets))]);
  }
}

/// Writes the rays that hit and keeps the others open, in order (so in their buckets, whose
/// starts move down with them); the number still open.
std::size_t close_hits(BundleScratch& s, std::size_t n, std::span<float> out) {
  std::size_t open = 0;
  std::size_t bucket = 0;
  for (std::size_t k = 0; k < n; ++k) {
    while (s.starts[bucket + 1] <= k) s.starts[++bucket] = static_cast<std::uint32_t>(open);
    if (s.best[k] != kNoHit) {
      out[s.ray_of[k]] = s.best[k];
      continue;
    }
    s.px[open] = s.px[k];
    s.py[open] = s.py[k];
    s.ix[open] = s.ix[k];
    s.iy[open] = s.iy[k];
    s.wx[open] = s.wx[k];
    s.wy[open] = s.wy[k];
    s.ray_of[open] = s.ray_of[k];
    s.best[open] = kNoHit;
    ++open;
  }
  while (bucket + 1 < s.starts.size()) s.starts[++bucket] = static_cast<std::uint32_t>(open);
  return open;
}

/// Strips along the wedge until every ray has hit, the strips leave the map or lie beyond
/// `reach` (cells): each ray's range in cells into `out` (by place in the group), or kNoHit.
void walk_strips(const CellMask& m, const BitMask& bits, const Wedge& w, std::size_t n, float reach,
                 std::span<float> out, BundleScratch& s) {
  const int major_count = w.along_x ? m.width : m.height;
  const int minor_count = w.along_x ? m.height : m.width;
  const float window = near_window(m);
  // Strips on a fixed partition of the map's major cells, the first holding the rearmost
  // origin: every ray meets the same strips ahead of it in any bundle, and so closes after the
  // same one (a wall's reach past its end can give a ray a hit a hair short of a box's face in
  // the next strip, so where strips end decides between such hits).
  const int first = static_cast<int>(std::floor(w.sign > 0 ? w.m0 : w.m1));
  int c =
      (first >= 0 ? first / kStripCells : (first - kStripCells + 1) / kStripCells) * kStripCells;
  while (n > 0) {
    const int lo = c;
    const int hi = c + kStripCells - 1;
    if (hi < 0 || lo >= major_count) break;
    // How far along the major axis the rays have travelled in this strip, and where across.
    const float a = static_cast<float>(lo) - w.ref;
    const float b = static_cast<float>(hi + 1) - w.ref;
    const float spread = 0.5F * (w.m1 - w.m0);
    if (std::min(std::abs(a), std::abs(b)) - spread > reach && a * b > 0.0F) break;
    const float pa = w.slope_lo * a;
    const float pb = w.slope_lo * b;
    const float pc = w.slope_hi * a;
    const float pd = w.slope_hi * b;
    const float minor_lo = s.key_origin + std::min(std::min(pa, pb), std::min(pc, pd));
    const float minor_hi = s.key_top + std::max(std::max(pa, pb), std::max(pc, pd));
    const int jlo = std::max(0, static_cast<int>(std::floor(minor_lo)) - 1);
    const int jhi = std::min(minor_count - 1, static_cast<int>(std::floor(minor_hi)) + 1);
    collect_boxes(bits, w, std::max(lo, 0), std::min(hi, major_count - 1), jlo, jhi, s.boxes);
    if (!s.boxes.empty()) {
      hit_boxes(m, w, window, s);
      n = close_hits(s, n, out);
    }
    c += w.sign * kStripCells;
  }
  for (std::size_t k = 0; k < n; ++k) out[s.ray_of[k]] = kNoHit;
}

/// A heading bin from the "diamond angle" (0-4 around the circle, monotonic in the heading:
/// no atan2).
int heading_bin(double c, double s, int bins) {
  const double diamond = s >= 0.0 ? (c >= 0.0 ? s / (c + s) : 1.0 - c / (s - c))
                                  : (c < 0.0 ? 2.0 - s / (-c - s) : 3.0 + c / (c - s));
  return std::clamp(static_cast<int>(diamond * (bins / 4)), 0, bins - 1);
}

constexpr std::uint64_t kUngrouped = ~std::uint64_t{0};

/// Particle p's group (block, then heading bin) in the high 32 bits, p in the low ones, so that
/// every key differs and a group's particles sort in index order; kUngrouped for a sensor that
/// is not finite, not on the map or in a blocking cell.
std::uint64_t group_key(const CellMask& m, const SensorFrame& s, std::size_t p, BundleGrouping g) {
  if (!s.finite || m.blocks_start(s.ox, s.oy)) return kUngrouped;
  const int i = m.cell_of(s.ox, m.width);
  const int j = m.cell_of(s.oy, m.height);
  if (i < 0 || j < 0 || i >= m.width || j >= m.height) return kUngrouped;
  const auto blocks_w = static_cast<std::uint64_t>((m.width + g.block_cells - 1) / g.block_cells);
  const std::uint64_t block = static_cast<std::uint64_t>(j / g.block_cells) * blocks_w +
                              static_cast<std::uint64_t>(i / g.block_cells);
  const auto bin = static_cast<std::uint64_t>(heading_bin(s.c, s.s, g.heading_bins));
  return (block * static_cast<std::uint64_t>(g.heading_bins) + bin) << 32 |
         static_cast<std::uint64_t>(p);
}

}  // namespace

double part_group_size(const BatchRays& rays, const CellMask& m, std::size_t part) {
  const std::size_t n = rays.particles();
  const std::array<std::size_t, 2> begins{0, n / 2 / part * part};
  // Per part: sensors in a group, distinct groups (the parts in parallel: each sorts its keys).
  std::array<std::pair<std::size_t, std::size_t>, 2> counts{};
  par::for_each_chunk(begins[1] == 0 ? 1 : 2, 1, [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      std::vector<std::uint64_t> groups;
      for (std::size_t p = begins[k]; p < std::min(n, begins[k] + part); ++p) {
        const std::uint64_t key = group_key(m, rays.sensor(p), p, BundleGrouping{});
        if (key != kUngrouped) groups.push_back(key >> 32);
      }
      std::sort(groups.begin(), groups.end());
      const auto distinct = std::unique(groups.begin(), groups.end()) - groups.begin();
      counts[k] = {groups.size(), static_cast<std::size_t>(distinct)};
    }
  });
  const std::size_t grouped = counts[0].first + counts[1].first;
  const std::size_t distinct = counts[0].second + counts[1].second;
  return distinct == 0 ? 0.0 : static_cast<double>(grouped) / static_cast<double>(distinct);
}

bool bundles_pay(const BatchRays& rays, const CellMask& m, double min_mean) {
  return part_group_size(rays, m, kPreparedPart) >= min_mean;
}

BitMask::BitMask(const CellMask& m)
    : row_words_(static_cast<std::size_t>(m.width) / 64 + 2),
      column_words_(static_cast<std::size_t>(m.height) / 64 + 2),
      rows_(row_words_ * static_cast<std::size_t>(m.height)),
      columns_(column_words_ * static_cast<std::size_t>(m.width)) {
  for (int j = 0; j < m.height; ++j) {
    for (int i = 0; i < m.width; ++i) {
      if (!m.blocks(i, j)) continue;
      const auto ui = static_cast<std::size_t>(i);
      const auto uj = static_cast<std::size_t>(j);
      rows_[uj * row_words_ + ui / 64] |= std::uint64_t{1} << (ui % 64);
      columns_[ui * column_words_ + uj / 64] |= std::uint64_t{1} << (uj % 64);
    }
  }
}

std::uint64_t BitMask::bits(bool along_x, int line, int first) const noexcept {
  const std::size_t words = along_x ? column_words_ : row_words_;
  const std::uint64_t* w =
      (along_x ? columns_.data() : rows_.data()) + static_cast<std::size_t>(line) * words;
  const auto at = static_cast<std::size_t>(first);
  const std::size_t shift = at % 64;
  const std::uint64_t low = w[at / 64] >> shift;
  return shift == 0 ? low : low | (w[at / 64 + 1] << (64 - shift));
}

BundleGroups group_for_bundles(const BatchRays& rays, const CellMask& m, std::size_t grain,
                               std::size_t min_size, BundleGrouping grouping) {
  const std::size_t n = rays.particles();
  BundleGroups groups;
  groups.sensors.resize(n);
  groups.grouped.assign(n, 0);
  // Key: block, then heading bin, then the particle's index (so every key differs and the
  // order is the indices' within a group).
  std::vector<std::uint64_t> keys(n);
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      groups.sensors[p] = rays.sensor(p);
      keys[p] = group_key(m, groups.sensors[p], p, grouping);
    }
  });
  std::sort(keys.begin(), keys.end());
  groups.starts.push_back(0);
  for (std::size_t k = 0; k < n && keys[k] != kUngrouped;) {
    std::size_t end = k;
    while (end < n && keys[end] >> 32 == keys[k] >> 32) ++end;
    if (end - k >= min_size) {
      for (std::size_t q = k; q < end; ++q) {
        const auto p = static_cast<std::uint32_t>(keys[q] & 0xFFFFFFFFU);
        groups.particles.push_back(p);
        groups.grouped[p] = 1;
      }
      groups.starts.push_back(static_cast<std::uint32_t>(groups.particles.size()));
    }
    k = end;
  }
  return groups;
}

namespace {

/// The rays of beam b from the chosen sensors, walked one by one (a bundle these strips cannot
/// cut).
void walk_each(const BatchRays& rays, const CellMask& m, const BundleGroups& groups,
               std::span<const std::uint32_t> particles, std::size_t b, std::span<float> ranges,
               const BundleScratch& s) {
  for (const std::uint32_t k : s.chosen) {
    const std::uint32_t p = particles[k];
    ranges[std::size_t{p} * rays.beams() + b] =
        walk_grid(m, rays.ray(groups.sensors[p], b), rays.max_range());
  }
}

}  // namespace

void cast_bundle_group(const BatchRays& rays, const CellMask& m, const BitMask& bits,
                       const BundleGroups& groups, std::size_t group, std::span<float> ranges,
                       BundleScratch& s, BeamRange beam_range, std::optional<float> only) {
  const std::span<const std::uint32_t> particles = groups.group(group);
  const std::size_t members = particles.size();
  const std::size_t beams = rays.beams();
  const float max_range = rays.max_range();
  const auto inv_res = 1.0 / static_cast<double>(m.resolution);
  for (auto* v : {&s.gx, &s.gy}) v->resize(members);
  for (std::size_t k = 0; k < members; ++k) {
    const SensorFrame& f = groups.sensors[particles[k]];
    s.gx[k] = static_cast<float>(f.ox * inv_res);
    s.gy[k] = static_cast<float>(f.oy * inv_res);
  }
  for (std::size_t b = beam_range.first; b < beam_range.second; ++b) {
    s.chosen.clear();
    for (std::size_t k = 0; k < members; ++k) {
      if (!only || ranges[std::size_t{particles[k]} * beams + b] == *only) {
        s.chosen.push_back(static_cast<std::uint32_t>(k));
      }
    }
    const std::size_t n = s.chosen.size();
    if (n == 0) continue;
    for (auto* v : {&s.ox, &s.oy, &s.dx, &s.dy, &s.key, &s.cells, &s.px, &s.py, &s.ix, &s.iy, &s.wx,
                    &s.wy, &s.best}) {
      v->resize(n);
    }
    for (auto* v : {&s.bucket, &s.order, &s.ray_of}) v->resize(n);
    for (auto* v : {&s.qx, &s.qy, &s.qdx, &s.qdy}) v->resize(n);
    const double cb = rays.beam_cos(b);
    const double sb = rays.beam_sin(b);
    for (std::size_t k = 0; k < n; ++k) {  // as BatchRays::ray
      const std::uint32_t g = s.chosen[k];
      const SensorFrame& f = groups.sensors[particles[g]];
      s.qx[k] = f.ox;
      s.qy[k] = f.oy;
      s.qdx[k] = snap_direction(f.c * cb - f.s * sb);
      s.qdy[k] = snap_direction(f.s * cb + f.c * sb);
      s.ox[k] = s.gx[g];
      s.oy[k] = s.gy[g];
      s.dx[k] = static_cast<float>(s.qdx[k]);
      s.dy[k] = static_cast<float>(s.qdy[k]);
    }
    Wedge w;
    if (!wedge_of(s, n, w)) {
      walk_each(rays, m, groups, particles, b, ranges, s);
      continue;
    }
    load_buckets(w, n, near_window(m), s);
    walk_strips(m, bits, w, n, max_range / m.resolution, s.cells, s);
    for (std::size_t k = 0; k < n; ++k) {
      const float c = s.cells[k];
      ranges[std::size_t{particles[s.chosen[k]]} * beams + b] =
          c == kNoHit ? max_range : std::min(c * m.resolution, max_range);
    }
  }
}

void cast_bundles(const BatchRays& rays, const CellMask& m, const BitMask& bits,
                  const BundleGroups& groups, std::span<float> ranges, std::optional<float> only) {
  const std::size_t beams = rays.beams();
  const std::size_t blocks = (beams + kBundleBeams - 1) / kBundleBeams;
  par::for_each_chunk(groups.count() * blocks, 1, [&](std::size_t begin, std::size_t end) {
    BundleScratch scratch;
    for (std::size_t item = begin; item < end; ++item) {
      const std::size_t first = item % blocks * kBundleBeams;
      cast_bundle_group(rays, m, bits, groups, item / blocks, ranges, scratch,
                        {first, std::min(beams, first + kBundleBeams)}, only);
    }
  });
}

}  // namespace mote::detail
