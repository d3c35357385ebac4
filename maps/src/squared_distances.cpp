// The saturated transform: the column pass writes |j - j'| (capped at the saturation n) into the
// output, the row pass replaces each row by its lower envelope of parabolas (Felzenszwalb and
// Huttenlocher 2012, algorithm DT(f)). Capping is exact below the cap: a parabola whose column
// distance reaches n contributes at least n^2 wherever it is lowest, so the minimum is either
// unchanged or at least n^2, which both clamp to n^2.
#include "mote/maps/squared_distances.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"

namespace mote {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The obstacle test of one rule at cell (i, j), cells row-major from the bottom row.
template <ObstacleCells Rule>
bool obstacle(const CellState* cells, std::size_t w, std::size_t h, std::size_t i,
              std::size_t j) noexcept {
  const CellState s = cells[j * w + i];
  if constexpr (Rule == ObstacleCells::kOccupied) return s == CellState::kOccupied;
  if constexpr (Rule == ObstacleCells::kOccupiedOrUnknown) return s != CellState::kFree;
  if constexpr (Rule == ObstacleCells::kNotOccupied) return s != CellState::kOccupied;
  if constexpr (Rule == ObstacleCells::kSurface) {
    if (s != CellState::kOccupied) return false;
    const CellState* c = cells + j * w + i;
    return (i > 0 && c[-1] == CellState::kFree) || (i + 1 < w && c[1] == CellState::kFree) ||
           (j > 0 && c[-static_cast<std::ptrdiff_t>(w)] == CellState::kFree) ||
           (j + 1 < h && c[w] == CellState::kFree);
  }
  return false;
}

/// Column pass, a chunk of columns at a time, rows in memory order (the inner loop is
/// contiguous): a sweep up then a sweep down, distances capped at n.
template <ObstacleCells Rule>
void column_pass(const OccupancyGrid& grid, std::uint16_t n, std::uint16_t* g) {
  const auto w = static_cast<std::size_t>(grid.width());
  const auto h = static_cast<std::size_t>(grid.height());
  const CellState* cells = grid.cells().data();
  par::for_each_chunk(w, /*grain=*/256, [&](std::size_t c0, std::size_t c1) {
    for (std::size_t i = c0; i < c1; ++i) g[i] = obstacle<Rule>(cells, w, h, i, 0) ? 0 : n;
    for (std::size_t j = 1; j < h; ++j) {
      const std::uint16_t* below = g + (j - 1) * w;
      std::uint16_t* row = g + j * w;
      for (std::size_t i = c0; i < c1; ++i) {
        const auto up = static_cast<std::uint16_t>(std::min<int>(below[i] + 1, n));
        row[i] = obstacle<Rule>(cells, w, h, i, j) ? std::uint16_t{0} : up;
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

/// The largest saturation the window pass takes: its sums n^2 + (n - 1)^2 fit int16 lanes.
constexpr std::uint16_t kMaxWindowSaturation = 127;

/// Row pass in place by a window: min over |d| < n of d^2 + g(q + d)^2, capped at n^2; a column
/// n or more away adds at least n^2. 2n - 1 passes of a vector min over the row, with no
/// division and no dependency from one cell to the next: several times the envelope's speed
/// for the few tens of cells a likelihood field's clamp spans. Exact integers, so the same
/// minimum as the envelope's.
void window_row_pass(std::size_t w, std::size_t h, std::uint16_t n, std::uint16_t* g) {
  const auto cap = static_cast<std::int16_t>(n * n);
  const std::size_t pad = n;
  par::for_each_chunk(h, /*grain=*/16, [&](std::size_t r0, std::size_t r1) {
    std::vector<std::int16_t> squared(w + 2 * pad, cap);  // g^2, cap beyond the row's ends
    std::vector<std::int16_t> best(w);
    for (std::size_t j = r0; j < r1; ++j) {
      std::uint16_t* row = g + j * w;
      std::int16_t lowest = cap;
      std::int16_t* sq = squared.data() + pad;
      for (std::size_t i = 0; i < w; ++i) {
        sq[i] = static_cast<std::int16_t>(row[i] * row[i]);
        lowest = std::min(lowest, sq[i]);
      }
      if (lowest == cap) {  // no obstacle within n cells of this row
        std::fill(row, row + w, static_cast<std::uint16_t>(cap));
        continue;
      }
      std::int16_t* out = best.data();
      std::copy(sq, sq + w, out);
      for (std::size_t d = 1; d < n; ++d) {
        const auto dd = static_cast<std::int16_t>(d * d);
        const std::int16_t* left = sq - d;
        const std::int16_t* right = sq + d;
        for (std::size_t q = 0; q < w; ++q) {
          const auto v = static_cast<std::int16_t>(std::min(left[q], right[q]) + dd);
          out[q] = std::min(out[q], v);
        }
        // Columns d + 1 or more away add at least (d + 1)^2: once every cell is there, stop.
        if (d % 4 == 3 && *std::max_element(out, out + w) <= static_cast<int>((d + 1) * (d + 1))) {
          break;
        }
      }
      for (std::size_t q = 0; q < w; ++q) {
        row[q] = static_cast<std::uint16_t>(std::min(out[q], cap));
      }
    }
  });
}

void row_pass(std::size_t w, std::size_t h, std::uint16_t n, std::uint16_t* g) {
  if (n <= kMaxWindowSaturation) {
    window_row_pass(w, h, n, g);
  } else {
    envelope_row_pass(w, h, n, g);
  }
}

}  // namespace

namespace detail {

void squared_distances(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
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
  row_pass(static_cast<std::size_t>(grid.width()), static_cast<std::size_t>(grid.height()), n, out);
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
  squared_ = std::make_unique_for_overwrite<std::uint16_t[]>(grid.cell_count());
  detail::squared_distances(grid, obstacles, n, squared_.get());
}

float SquaredDistances::distance(std::uint32_t s) const noexcept {
  // DistanceField's expression: double sqrt times resolution, to float, then the clamp.
  const auto d = static_cast<float>(std::sqrt(static_cast<double>(s)) * resolution_);
  return std::min(d, clamp_);
}

}  // namespace mote
