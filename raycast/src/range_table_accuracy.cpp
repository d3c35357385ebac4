#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "mote/raycast/range_table.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote {

namespace {

/// A tiled table's rays start in a few tiles only, so that measuring builds no more of them
/// than the budget holds (kMaxTiles at most): the free cells, off the tiles' borders, of tiles
/// drawn by the free cells the generator picks. Empty (every free cell) for a whole table.
std::vector<std::uint32_t> origins_pool(const RangeTable& table, const OccupancyGrid& grid,
                                        std::mt19937_64& rng) {
  const RangeTableStats& s = table.stats();
  if (s.tile_cells == 0) return {};
  constexpr std::size_t kMaxTiles = 8;
  const auto& free = grid.free_cells();
  const auto w = static_cast<std::uint32_t>(grid.width());
  const auto edge = static_cast<std::uint32_t>(s.tile_cells);
  const auto tile_of = [&](std::uint32_t cell) {
    return std::pair{cell % w / edge, cell / w / edge};
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> tiles;
  for (int draw = 0; draw < 1000 && tiles.size() < std::min(kMaxTiles, s.max_resident_tiles);
       ++draw) {
    const auto t = tile_of(free[rng() % free.size()]);
    if (std::find(tiles.begin(), tiles.end(), t) == tiles.end()) tiles.push_back(t);
  }
  // Not the tiles' border cells: a ray from one reads its neighbour tile too, which the budget
  // may not hold beside the drawn ones (each such ray would build and evict a tile).
  const auto border = [&](std::uint32_t cell) {
    const std::uint32_t i = cell % w % edge;
    const std::uint32_t j = cell / w % edge;
    return i == 0 || j == 0 || i + 1 == edge || j + 1 == edge;
  };
  std::vector<std::uint32_t> pool;
  for (const std::uint32_t cell : free) {
    if (border(cell)) continue;
    if (std::find(tiles.begin(), tiles.end(), tile_of(cell)) != tiles.end()) pool.push_back(cell);
  }
  return pool;
}

}  // namespace

RangeTableAccuracy measure_range_table(const RangeTable& table, const RayCaster& exact,
                                       const OccupancyGrid& grid, std::size_t rays, float max_range,
                                       std::uint64_t seed) {
  RangeTableAccuracy acc;
  if (grid.free_cells().empty() || rays == 0) return acc;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<std::uint32_t> pool = origins_pool(table, grid, rng);
  const auto& free = pool.empty() ? grid.free_cells() : pool;
  std::vector<double> errors;
  errors.reserve(rays);
  const double cell = grid.resolution();
  for (std::size_t k = 0; k < rays; ++k) {
    const auto f = static_cast<std::size_t>(unit(rng) * static_cast<double>(free.size()));
    const std::uint32_t start = free[std::min(f, free.size() - 1)];
    // v before u: the order GCC evaluated them in as arguments of free_point, which this
    // replaced, so the figures measured before (BENCHMARKS.md) stay the same.
    const double v = unit(rng);
    const double u = unit(rng);
    const Point2 o = grid.point_in_cell(start, u, v);
    const double angle = (2.0 * unit(rng) - 1.0) * std::numbers::pi;
    const double e = std::abs(double(table.cast_one(o, angle, max_range)) -
                              double(exact.cast_one(o, angle, max_range))) /
                     cell;
    if (e > acc.max_cells || errors.empty()) {
      acc.max_cells = e;
      acc.worst_origin = o;
      acc.worst_angle = angle;
    }
    errors.push_back(e);
  }
  acc.rays = errors.size();
  const auto share = [&](double limit) {
    return static_cast<double>(std::count_if(errors.begin(), errors.end(),
                                             [limit](double e) { return e <= limit; })) /
           static_cast<double>(errors.size());
  };
  acc.within_one_cell = share(1.0);
  acc.within_two_cells = share(2.0);
  std::sort(errors.begin(), errors.end());
  acc.median_cells = errors[errors.size() / 2];
  acc.p99_cells = errors[std::min(errors.size() - 1, errors.size() * 99 / 100)];
  return acc;
}

}  // namespace mote
