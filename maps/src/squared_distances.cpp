// The saturated transform by the envelope, for clamps past squared_rows.cpp's window: the column
// pass writes |j - j'| (capped at the saturation n) into the output, the row pass replaces each
// row by its lower envelope of parabolas (Felzenszwalb and Huttenlocher 2012, algorithm DT(f)).
// Capping is exact below the cap: a parabola whose column distance reaches n contributes at least
// n^2 wherever it is lowest, so the minimum is either unchanged or at least n^2, which both clamp
// to n^2.
#include "mote/maps/squared_distances.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/core/parallel.hpp"
#include "squared_envelope.hpp"

namespace mote {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Column pass, a chunk of columns at a time, rows in memory order (the inner loop is
/// contiguous): a sweep up then a sweep down, distances capped at n.
template <ObstacleCells Rule>
void column_pass(const OccupancyGrid& grid, std::uint16_t n, std::uint16_t* g) {
  const auto w = static_cast<std::size_t>(grid.width());
  const auto h = static_cast<std::size_t>(grid.height());
  const CellState* cells = grid.cells().data();
  par::for_each_chunk(w, /*grain=*/256, [&](std::size_t c0, std::size_t c1) {
    for (std::size_t i = c0; i < c1; ++i) g[i] = detail::obstacle<Rule>(cells, w, h, i, 0) ? 0 : n;
    for (std::size_t j = 1; j < h; ++j) {
      const std::uint16_t* below = g + (j - 1) * w;
      std::uint16_t* row = g + j * w;
      for (std::size_t i = c0; i < c1; ++i) {
        const auto up = static_cast<std::uint16_t>(std::min<int>(below[i] + 1, n));
        row[i] = detail::obstacle<Rule>(cells, w, h, i, j) ? std::uint16_t{0} : up;
      }
    }
    for (std::size_t j = h - 1; j-- > 0;) {
      const std::uint16_t* above = g + (j + 1) * w;
      std::uint16_t* row = g + j * w;
      for (std::size_t i = c0; i < c1; ++i) {
        row[i] = std::min(row[i], static_cast<std::uint16_t>(above[i] + 1));
      }
    }
  });
}

/// One row's lower envelope: vertices v, boundaries z, heights f (F&H section 2.1).
struct Envelope {
  std::vector<std::int32_t> v;
  std::vector<double> z;
  std::vector<double> f;
  explicit Envelope(std::size_t n) : v(n), z(n + 1), f(n) {}

  [[nodiscard]] double intersect(std::int32_t q, std::int32_t p) const noexcept {
    const double dq = q;
    const double dp = p;
    return ((f[static_cast<std::size_t>(q)] + dq * dq) -
            (f[static_cast<std::size_t>(p)] + dp * dp)) /
           (2.0 * (dq - dp));
  }

  /// The envelope of the finite parabolas of f; returns their count.
  std::size_t build(std::size_t n) {
    std::size_t k = 0;
    for (std::size_t qi = 0; qi < n; ++qi) {
      if (f[qi] == kInf) continue;
      const auto q = static_cast<std::int32_t>(qi);
      if (k == 0) {
        v[0] = q;
        z[0] = -kInf;
        z[1] = kInf;
        k = 1;
        continue;
      }
      double s = intersect(q, v[k - 1]);
      while (s <= z[k - 1]) {  // z[0] = -inf stops this before k reaches 0
        --k;
        s = intersect(q, v[k - 1]);
      }
      v[k] = q;
      z[k] = s;
      z[k + 1] = kInf;
      ++k;
    }
    return k;
  }
};

/// Row pass in place by the envelope: g row -> min(min_p (q - p)^2 + g(p)^2, n^2). Columns at
/// the cap add no parabola (see the file comment). Any saturation.
void envelope_row_pass(std::size_t w, std::size_t h, std::uint16_t n, std::uint16_t* g) {
  const auto cap = static_cast<double>(n) * n;
  par::for_each_chunk(h, /*grain=*/16, [&](std::size_t r0, std::size_t r1) {
    Envelope e(w);
    for (std::size_t j = r0; j < r1; ++j) {
      std::uint16_t* row = g + j * w;
      for (std::size_t i = 0; i < w; ++i) {
        e.f[i] = row[i] >= n ? kInf : static_cast<double>(row[i]) * row[i];
      }
      if (e.build(w) == 0) {
        std::fill(row, row + w, static_cast<std::uint16_t>(cap));
        continue;
      }
      std::size_t k = 0;
      for (std::size_t q = 0; q < w; ++q) {
        while (e.z[k + 1] < static_cast<double>(q)) ++k;
        const auto p = static_cast<std::size_t>(e.v[k]);
        const double dq = static_cast<double>(q) - static_cast<double>(p);
        row[q] = static_cast<std::uint16_t>(std::min(dq * dq + e.f[p], cap));
      }
    }
  });
}

}  // namespace

namespace detail {

void envelope_squared_distances(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
                                std::uint16_t* out) {
  const auto n = static_cast<std::uint16_t>(saturation);
  switch (obstacles) {
    case ObstacleCells::kOccupied:
      column_pass<ObstacleCells::kOccupied>(grid, n, out);
      break;
    case ObstacleCells::kOccupiedOrUnknown:
      column_pass<ObstacleCells::kOccupiedOrUnknown>(grid, n, out);
      break;
    case ObstacleCells::kSurface:
      column_pass<ObstacleCells::kSurface>(grid, n, out);
      break;
    case ObstacleCells::kNotOccupied:
      column_pass<ObstacleCells::kNotOccupied>(grid, n, out);
      break;
  }
  envelope_row_pass(static_cast<std::size_t>(grid.width()), static_cast<std::size_t>(grid.height()),
                    n, out);
}

}  // namespace detail

int SquaredDistances::saturation(double resolution, float clamp, int max_cells) {
  if (!(clamp > 0.0F) || !std::isfinite(clamp) || !(resolution > 0.0)) return 0;
  const double cells = std::ceil(static_cast<double>(clamp) / resolution);
  if (cells > max_cells) return 0;
  auto n = std::max(1, static_cast<int>(cells));
  // The distance of n cells, computed as DistanceField computes it, must reach the clamp.
  while (n <= max_cells &&
         static_cast<float>(std::sqrt(static_cast<double>(n) * n) * resolution) < clamp) {
    ++n;
  }
  return n <= max_cells ? n : 0;
}

SquaredDistances::SquaredDistances(const OccupancyGrid& grid, ObstacleCells obstacles, float clamp)
    : width_(grid.width()),
      height_(grid.height()),
      resolution_(grid.resolution()),
      origin_(grid.origin()),
      clamp_(clamp),
      cap_(0) {
  const int n = saturation(resolution_, clamp, kMaxSaturation);
  if (n == 0) {
    std::string message = "squared distances: the clamp must be positive, finite and at most ";
    message.append(std::to_string(kMaxSaturation)).append(" cells, got ");
    message.append(std::to_string(clamp)).append(" m");
    throw ConfigError(message);
  }
  cap_ = static_cast<std::uint32_t>(n) * static_cast<std::uint32_t>(n);
  // Every value is written by the transform: no zeroing first.
  squared_ = huge_pages::uninitialized<std::uint16_t>(grid.cell_count());
  const auto w = static_cast<std::size_t>(width_);
  for_each_squared_row(
      grid, obstacles, n,
      [&](std::size_t j, std::size_t i0, std::size_t count, const std::uint16_t* s) {
        std::copy(s, s + count, squared_.get() + j * w + i0);
      });
}

float SquaredDistances::distance(std::uint32_t s) const noexcept {
  // DistanceField's expression: double sqrt times resolution, to float, then the clamp.
  const auto d = static_cast<float>(std::sqrt(static_cast<double>(s)) * resolution_);
  return std::min(d, clamp_);
}

}  // namespace mote
