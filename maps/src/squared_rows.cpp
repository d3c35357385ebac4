// The saturated transform a band of rows at a time: per row the distance h to the nearest
// obstacle along the row (two sweeps), then per output row j the minimum over |d| < n of
// d^2 + h(j + d)^2, each d one vector pass over the row. A chunk of output rows computes the h
// of its rows and of the n - 1 rows on either side, so nothing grid-sized is allocated. Exact:
// an obstacle n or more rows away adds at least n^2, the cap.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/core/parallel.hpp"
#include "mote/maps/squared_distances.hpp"
#include "squared_envelope.hpp"

namespace mote {

namespace {

/// The largest saturation of the band: its sums n^2 + (n - 1)^2 fit int16 vector lanes.
constexpr int kMaxBandSaturation = 127;
/// Output rows per chunk: the halo of 2 (n - 1) rows costs a fraction of the row sweeps.
constexpr std::size_t kBandRows = 256;

/// The largest and the smallest of n values, as loops that vectorize (std::max_element's
/// iterator result does not).
std::int16_t largest(const std::int16_t* v, std::size_t n) {
  std::int16_t m = 0;
  for (std::size_t i = 0; i < n; ++i) m = std::max(m, v[i]);
  return m;
}
std::int16_t smallest(const std::int16_t* v, std::size_t n) {
  std::int16_t m = std::numeric_limits<std::int16_t>::max();
  for (std::size_t i = 0; i < n; ++i) m = std::min(m, v[i]);
  return m;
}

/// h^2 of row j: the distance along the row to the nearest obstacle, capped at n.
template <ObstacleCells Rule>
void row_distances(const OccupancyGrid& grid, std::size_t j, std::int16_t n, std::int16_t* out) {
  const auto w = static_cast<std::size_t>(grid.width());
  const auto h = static_cast<std::size_t>(grid.height());
  const CellState* cells = grid.cells().data();
  std::int16_t run = n;
  for (std::size_t i = 0; i < w; ++i) {
    run = detail::obstacle<Rule>(cells, w, h, i, j) ? std::int16_t{0}
                                                    : std::min<std::int16_t>(run + 1, n);
    out[i] = run;
  }
  run = n;
  for (std::size_t i = w; i-- > 0;) {
    run = std::min<std::int16_t>(out[i], run + 1);
    out[i] = static_cast<std::int16_t>(run * run);
  }
}

/// Columns per segment: the unit in which the column window skips rows without obstacles.
constexpr std::size_t kSegment = 256;

/// h^2 of a band of rows and, per row and segment of columns, its smallest value: a segment at
/// the cap has no obstacle within n cells along its row and cannot lower any cell.
struct Band {
  std::size_t first = 0;  // its first grid row
  std::size_t width = 0;
  std::size_t segments = 0;
  std::vector<std::int16_t> squared;  // rows x width
  std::vector<std::int16_t> lowest;   // rows x segments

  [[nodiscard]] const std::int16_t* row(std::size_t j) const {
    return squared.data() + (j - first) * width;
  }
  [[nodiscard]] std::int16_t low(std::size_t j, std::size_t s) const {
    return lowest[(j - first) * segments + s];
  }
};

template <ObstacleCells Rule>
void fill_band(const OccupancyGrid& grid, std::size_t b0, std::size_t b1, std::int16_t n,
               Band& band) {
  band.first = b0;
  band.width = static_cast<std::size_t>(grid.width());
  band.segments = (band.width + kSegment - 1) / kSegment;
  huge_pages::reserve(band.squared, (b1 - b0) * band.width);
  band.squared.resize((b1 - b0) * band.width);
  band.lowest.resize((b1 - b0) * band.segments);
  for (std::size_t j = b0; j < b1; ++j) {
    std::int16_t* hj = band.squared.data() + (j - b0) * band.width;
    row_distances<Rule>(grid, j, n, hj);
    for (std::size_t s = 0; s < band.segments; ++s) {
      const std::size_t end = std::min(band.width, (s + 1) * kSegment);
      band.lowest[(j - b0) * band.segments + s] = smallest(hj + s * kSegment, end - s * kSegment);
    }
  }
}

/// Segment s of output row j into best: the minimum over |d| <= halo of d^2 + h(j + d)^2,
/// skipping rows whose segment is at the cap, stopped once no farther row can lower a cell.
void column_window(const Band& band, std::size_t j, std::size_t h, std::size_t s, std::int16_t cap,
                   std::size_t halo, std::int16_t* best) {
  const std::size_t i0 = s * kSegment;
  const std::size_t len = std::min(band.width, i0 + kSegment) - i0;
  std::int16_t* b = best + i0;
  std::copy(band.row(j) + i0, band.row(j) + i0 + len, b);
  if (largest(b, len) <= 1) return;  // on or next to obstacles along the row: already exact
  for (std::size_t d = 1; d <= halo && (j >= d || j + d < h); ++d) {
    const bool below = j >= d && band.low(j - d, s) != cap;
    const bool above = j + d < h && band.low(j + d, s) != cap;
    const auto dd = static_cast<std::int16_t>(d * d);
    if (below && above) {
      const std::int16_t* lo = band.row(j - d) + i0;
      const std::int16_t* hi = band.row(j + d) + i0;
      for (std::size_t i = 0; i < len; ++i) {
        b[i] = std::min(b[i], static_cast<std::int16_t>(std::min(lo[i], hi[i]) + dd));
      }
    } else if (below || above) {
      const std::int16_t* one = band.row(below ? j - d : j + d) + i0;
      for (std::size_t i = 0; i < len; ++i) {
        b[i] = std::min(b[i], static_cast<std::int16_t>(one[i] + dd));
      }
    }
    // Rows d + 1 or more away add at least (d + 1)^2: once every cell is there, stop.
    if (d % 4 == 3 && largest(b, len) <= static_cast<int>((d + 1) * (d + 1))) {
      break;
    }
  }
}

/// The bands of one transform, each reused by the chunks that follow on its thread. Why: a band
/// is megabytes (6.5 MB at 9768 columns), which malloc maps fresh for every chunk, so each
/// chunk paid a page fault per 4 KB of it; now a transform touches at most one band per thread.
class BandPool {
 public:
  std::unique_ptr<Band> take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (free_.empty()) return std::make_unique<Band>();
    std::unique_ptr<Band> band = std::move(free_.back());
    free_.pop_back();
    return band;
  }
  void give_back(std::unique_ptr<Band> band) {
    const std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(band));
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<Band>> free_;
};

template <ObstacleCells Rule>
void band_rows(const OccupancyGrid& grid, int saturation, const SquaredRowPiece& piece) {
  const auto h = static_cast<std::size_t>(grid.height());
  const auto n = static_cast<std::int16_t>(saturation);
  const auto cap = static_cast<std::int16_t>(n * n);
  const auto halo = static_cast<std::size_t>(n - 1);
  BandPool pool;
  par::for_each_chunk(h, /*grain=*/kBandRows, [&](std::size_t r0, std::size_t r1) {
    std::unique_ptr<Band> taken = pool.take();
    Band& band = *taken;
    fill_band<Rule>(grid, r0 > halo ? r0 - halo : 0, std::min(h, r1 + halo), n, band);
    std::vector<std::int16_t> best(band.width);
    std::vector<std::uint16_t> out(kSegment);
    // A segment of columns at a time down the rows: its slice of the band stays in cache.
    for (std::size_t s = 0; s < band.segments; ++s) {
      const std::size_t i0 = s * kSegment;
      const std::size_t len = std::min(band.width, i0 + kSegment) - i0;
      for (std::size_t j = r0; j < r1; ++j) {
        column_window(band, j, h, s, cap, halo, best.data());
        for (std::size_t i = 0; i < len; ++i) {
          out[i] = static_cast<std::uint16_t>(std::min(best[i0 + i], cap));
        }
        piece(j, i0, len, out.data());
      }
    }
    pool.give_back(std::move(taken));
  });
}

/// Beyond the band's saturation: the whole transform, then the rows from it.
void envelope_rows(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
                   const SquaredRowPiece& piece) {
  const auto w = static_cast<std::size_t>(grid.width());
  const auto all = huge_pages::uninitialized<std::uint16_t>(grid.cell_count());
  detail::envelope_squared_distances(grid, obstacles, saturation, all.get());
  par::for_each_chunk(static_cast<std::size_t>(grid.height()), /*grain=*/16,
                      [&](std::size_t r0, std::size_t r1) {
                        for (std::size_t j = r0; j < r1; ++j) piece(j, 0, w, all.get() + j * w);
                      });
}

}  // namespace

void for_each_squared_row(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
                          const SquaredRowPiece& piece) {
  if (saturation < 1 || saturation > SquaredDistances::kMaxSaturation) {
    throw ConfigError("squared distances: saturation must be 1..255 cells");
  }
  if (saturation > kMaxBandSaturation) {
    envelope_rows(grid, obstacles, saturation, piece);
    return;
  }
  switch (obstacles) {
    case ObstacleCells::kOccupied:
      band_rows<ObstacleCells::kOccupied>(grid, saturation, piece);
      break;
    case ObstacleCells::kOccupiedOrUnknown:
      band_rows<ObstacleCells::kOccupiedOrUnknown>(grid, saturation, piece);
      break;
    case ObstacleCells::kSurface:
      band_rows<ObstacleCells::kSurface>(grid, saturation, piece);
      break;
    case ObstacleCells::kNotOccupied:
      band_rows<ObstacleCells::kNotOccupied>(grid, saturation, piece);
      break;
  }
}

}  // namespace mote
