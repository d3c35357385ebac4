// The saturated transform a band of rows at a time: per row the distance h to the nearest
// obstacle along the row (two sweeps), then per output row j the minimum over |d| < n of
// d^2 + h(j + d)^2, each d one vector pass over the row. A chunk of output rows computes the h
// of its rows and of the n - 1 rows on either side, so nothing grid-sized is allocated. Exact:
// an obstacle n or more rows away adds at least n^2, the cap.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "mote/maps/squared_distances.hpp"
#include "squared_envelope.hpp"

namespace mote {

namespace {

/// The largest saturation of the band: its sums n^2 + (n - 1)^2 fit int16 vector lanes.
constexpr int kMaxBandSaturation = 127;
/// Output rows per chunk: the halo of 2 (n - 1) rows costs a fraction of the row sweeps.
constexpr std::size_t kBandRows = 256;

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

template <ObstacleCells Rule>
void band_rows(const OccupancyGrid& grid, int saturation,
               const std::function<void(std::size_t, const std::uint16_t*)>& row) {
  const auto w = static_cast<std::size_t>(grid.width());
  const auto h = static_cast<std::size_t>(grid.height());
  const auto n = static_cast<std::int16_t>(saturation);
  const auto cap = static_cast<std::int16_t>(n * n);
  const auto halo = static_cast<std::size_t>(n - 1);
  par::for_each_chunk(h, /*grain=*/kBandRows, [&](std::size_t r0, std::size_t r1) {
    const std::size_t b0 = r0 > halo ? r0 - halo : 0;
    const std::size_t b1 = std::min(h, r1 + halo);
    std::vector<std::int16_t> band((b1 - b0) * w);  // h^2 of rows [b0, b1)
    std::vector<std::int16_t> lowest(b1 - b0);      // per band row, its smallest h^2
    for (std::size_t j = b0; j < b1; ++j) {
      std::int16_t* hj = band.data() + (j - b0) * w;
      row_distances<Rule>(grid, j, n, hj);
      lowest[j - b0] = *std::min_element(hj, hj + w);
    }
    std::vector<std::int16_t> best(w);
    std::vector<std::uint16_t> out(w);
    for (std::size_t j = r0; j < r1; ++j) {
      const std::size_t lo = j > halo ? j - halo : 0;
      const std::size_t hi = std::min(h, j + halo + 1);
      const bool none =
          *std::min_element(lowest.begin() + static_cast<std::ptrdiff_t>(lo - b0),
                            lowest.begin() + static_cast<std::ptrdiff_t>(hi - b0)) == cap;
      if (none) {  // no obstacle within n - 1 rows: every cell at the cap
        std::fill(out.begin(), out.end(), static_cast<std::uint16_t>(cap));
        row(j, out.data());
        continue;
      }
      const std::int16_t* hj = band.data() + (j - b0) * w;
      std::copy(hj, hj + w, best.begin());
      for (std::size_t d = 1; d <= halo && (j >= d || j + d < h); ++d) {
        const auto dd = static_cast<std::int16_t>(d * d);
        const std::int16_t* below = j >= d ? band.data() + (j - d - b0) * w : nullptr;
        const std::int16_t* above = j + d < h ? band.data() + (j + d - b0) * w : nullptr;
        std::int16_t* b = best.data();
        if (below != nullptr && above != nullptr) {
          for (std::size_t i = 0; i < w; ++i) {
            b[i] = std::min(b[i], static_cast<std::int16_t>(std::min(below[i], above[i]) + dd));
          }
        } else {
          const std::int16_t* one = below != nullptr ? below : above;
          for (std::size_t i = 0; i < w; ++i) {
            b[i] = std::min(b[i], static_cast<std::int16_t>(one[i] + dd));
          }
        }
        // Rows d + 1 or more away add at least (d + 1)^2: once every cell is there, stop.
        if (d % 4 == 3 && *std::max_element(b, b + w) <= static_cast<int>((d + 1) * (d + 1))) {
          break;
        }
      }
      for (std::size_t i = 0; i < w; ++i) {
        out[i] = static_cast<std::uint16_t>(std::min(best[i], cap));
      }
      row(j, out.data());
    }
  });
}

/// Beyond the band's saturation: the whole transform, then the rows from it.
void envelope_rows(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
                   const std::function<void(std::size_t, const std::uint16_t*)>& row) {
  const auto w = static_cast<std::size_t>(grid.width());
  const auto all = std::make_unique_for_overwrite<std::uint16_t[]>(grid.cell_count());
  detail::envelope_squared_distances(grid, obstacles, saturation, all.get());
  par::for_each_chunk(static_cast<std::size_t>(grid.height()), /*grain=*/16,
                      [&](std::size_t r0, std::size_t r1) {
                        for (std::size_t j = r0; j < r1; ++j) row(j, all.get() + j * w);
                      });
}

}  // namespace

void for_each_squared_row(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
                          const std::function<void(std::size_t, const std::uint16_t*)>& row) {
  if (saturation < 1 || saturation > SquaredDistances::kMaxSaturation) {
    throw ConfigError("squared distances: saturation must be 1..255 cells");
  }
  if (saturation > kMaxBandSaturation) {
    envelope_rows(grid, obstacles, saturation, row);
    return;
  }
  switch (obstacles) {
    case ObstacleCells::kOccupied:
      band_rows<ObstacleCells::kOccupied>(grid, saturation, row);
      break;
    case ObstacleCells::kOccupiedOrUnknown:
      band_rows<ObstacleCells::kOccupiedOrUnknown>(grid, saturation, row);
      break;
    case ObstacleCells::kSurface:
      band_rows<ObstacleCells::kSurface>(grid, saturation, row);
      break;
    case ObstacleCells::kNotOccupied:
      band_rows<ObstacleCells::kNotOccupied>(grid, saturation, row);
      break;
  }
}

}  // namespace mote
