#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "mote/raycast/range_table.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote {

RangeTableAccuracy measure_range_table(const RangeTable& table, const RayCaster& exact,
                                       const OccupancyGrid& grid, std::size_t rays, float max_range,
                                       std::uint64_t seed) {
  RangeTableAccuracy acc;
  if (grid.free_cell_count() == 0 || rays == 0) return acc;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto& free = grid.free_cells();
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
