// Felzenszwalb & Huttenlocher 2012: the 2D squared distance transform separates into a 1D pass
// down every column (here: nearest obstacle in the column, an integer) and a 1D lower envelope
// of parabolas along every row (their algorithm DT(f), section 2.1).
#include "mote/maps/distance_field.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"

namespace mote {

namespace {

/// "No obstacle in this column" for the column pass; small enough that +1 cannot overflow.
constexpr std::int32_t kNone = 0x3FFFFFFF;
constexpr double kInf = std::numeric_limits<double>::infinity();

bool is_obstacle(CellState s, bool unknown_too) noexcept {
  return s == CellState::kOccupied || (unknown_too && s == CellState::kUnknown);
}

/// Column pass: g[j][i] = |j - j'| to the nearest obstacle j' in column i, by a sweep up and a
/// sweep down. Rows are walked in memory order, a chunk of columns at a time, so the inner
/// loop runs along contiguous cells and vectorizes.
void column_pass(const OccupancyGrid& grid, bool unknown_too, std::vector<std::int32_t>& g) {
  const auto w = static_cast<std::size_t>(grid.width());
  const auto h = static_cast<std::size_t>(grid.height());
  const CellState* cells = grid.cells().data();
  par::for_each_chunk(w, /*grain=*/256, [&](std::size_t c0, std::size_t c1) {
    for (std::size_t i = c0; i < c1; ++i) g[i] = is_obstacle(cells[i], unknown_too) ? 0 : kNone;
    for (std::size_t j = 1; j < h; ++j) {
      const std::int32_t* below = g.data() + (j - 1) * w;
      std::int32_t* row = g.data() + j * w;
      for (std::size_t i = c0; i < c1; ++i) {
        row[i] = is_obstacle(cells[j * w + i], unknown_too) ? 0 : std::min(below[i] + 1, kNone);
      }
    }
    for (std::size_t j = h - 1; j-- > 0;) {
      const std::int32_t* above = g.data() + (j + 1) * w;
      std::int32_t* row = g.data() + j * w;
      for (std::size_t i = c0; i < c1; ++i) row[i] = std::min(row[i], above[i] + 1);
    }
  });
}

/// Scratch for the 1D transform of one row: parabola vertices v, boundaries z, heights f.
struct Envelope {
  std::vector<std::int32_t> v;
  std::vector<double> z;
  std::vector<double> f;
  explicit Envelope(std::size_t n) : v(n), z(n + 1), f(n) {}
};

/// Intersection abscissa of the parabolas rooted at q and p (F&H eq. in section 2.1).
double intersect(const std::vector<double>& f, std::int32_t q, std::int32_t p) noexcept {
  const double dq = q;
  const double dp = p;
  return ((f[static_cast<std::size_t>(q)] + dq * dq) - (f[static_cast<std::size_t>(p)] + dp * dp)) /
         (2.0 * (dq - dp));
}

/// Builds the lower envelope of the finite parabolas of e.f; returns their count.
std::size_t build_envelope(Envelope& e, std::size_t n) {
  std::size_t k = 0;  // number of parabolas in the envelope
  for (std::size_t qi = 0; qi < n; ++qi) {
    if (e.f[qi] == kInf) continue;  // columns without obstacles add no parabola
    const auto q = static_cast<std::int32_t>(qi);
    if (k == 0) {
      e.v[0] = q;
      e.z[0] = -kInf;
      e.z[1] = kInf;
      k = 1;
      continue;
    }
    double s = intersect(e.f, q, e.v[k - 1]);
    while (s <= e.z[k - 1]) {  // z[0] = -inf stops this before k reaches 0
      --k;
      s = intersect(e.f, q, e.v[k - 1]);
    }
    e.v[k] = q;
    e.z[k] = s;
    e.z[k + 1] = kInf;
    ++k;
  }
  return k;
}

/// Row pass: squared distance D(q) = min_p (q - p)^2 + g(p)^2, then metres, then the clamp.
void row_pass(const std::vector<std::int32_t>& g, std::size_t w, std::size_t h, double res,
              float clamp, std::vector<float>& out) {
  par::for_each_chunk(h, /*grain=*/16, [&](std::size_t r0, std::size_t r1) {
    Envelope e(w);
    for (std::size_t j = r0; j < r1; ++j) {
      const std::int32_t* gj = g.data() + j * w;
      float* dst = out.data() + j * w;
      for (std::size_t i = 0; i < w; ++i) {
        e.f[i] = gj[i] == kNone ? kInf : static_cast<double>(gj[i]) * gj[i];
      }
      if (build_envelope(e, w) == 0) {
        std::fill(dst, dst + w, clamp);
        continue;
      }
      std::size_t k = 0;
      for (std::size_t q = 0; q < w; ++q) {
        while (e.z[k + 1] < static_cast<double>(q)) ++k;
        const auto p = static_cast<std::size_t>(e.v[k]);
        const double dq = static_cast<double>(q) - static_cast<double>(p);
        const double squared = dq * dq + e.f[p];
        dst[q] = std::min(static_cast<float>(std::sqrt(squared) * res), clamp);
      }
    }
  });
}

}  // namespace

DistanceField::DistanceField(const OccupancyGrid& grid, DistanceFieldOptions options)
    : width_(grid.width()),
      height_(grid.height()),
      resolution_(grid.resolution()),
      origin_(grid.origin()),
      options_(options) {
  if (!(options.max_distance >= 0.0F)) {
    throw ConfigError("distance field: max_distance must be >= 0 m, got " +
                      std::to_string(options.max_distance));
  }
  const auto w = static_cast<std::size_t>(width_);
  const auto h = static_cast<std::size_t>(height_);
  std::vector<std::int32_t> column(w * h);
  column_pass(grid, options.unknown_is_obstacle, column);
  distances_.resize(w * h);
  row_pass(column, w, h, resolution_, options.max_distance, distances_);
}

}  // namespace mote
