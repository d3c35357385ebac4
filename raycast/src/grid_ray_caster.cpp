#include "mote/raycast/grid_ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mote/core/parallel.hpp"
#include "ray_setup.hpp"

namespace mote {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Clips the ray [0, t_max] (cell units) to the slab [0, size) along one axis; false when the
/// ray never enters it.
bool clip_axis(double o, double d, double size, double& t0, double& t1) {
  if (d == 0.0) return o >= 0.0 && o < size;
  double enter = (0.0 - o) / d;
  double leave = (size - o) / d;
  if (enter > leave) std::swap(enter, leave);
  t0 = std::max(t0, enter);
  t1 = std::min(t1, leave);
  return t0 < t1;
}

/// Per-axis state of the Amanatides-Woo walk: current cell, step, parameter t (cell units) of the
/// next cell boundary and the t between boundaries.
struct Axis {
  int cell;
  int step;
  double t_next;
  double t_delta;
};

Axis start_axis(double o, double d, double t0, int size) {
  const double at = std::floor(o + t0 * d);
  const int cell = static_cast<int>(std::clamp(at, 0.0, static_cast<double>(size - 1)));
  if (d == 0.0) return {cell, 0, kInf, kInf};
  const int step = d > 0.0 ? 1 : -1;
  const double boundary = d > 0.0 ? cell + 1.0 : static_cast<double>(cell);
  return {cell, step, (boundary - o) / d, 1.0 / std::abs(d)};
}

/// Range (m) along a grid frame ray to the first blocking cell, or max_range. The walk works in
/// cell units (origin divided by the resolution) so boundaries are the integers.
float walk(const detail::CellMask& mask, const detail::GridRay& ray, float max_range) {
  const double ox = ray.ox / mask.resolution;
  const double oy = ray.oy / mask.resolution;
  double t0 = 0.0;
  double t1 = static_cast<double>(max_range) / mask.resolution;
  if (!clip_axis(ox, ray.dx, mask.width, t0, t1) || !clip_axis(oy, ray.dy, mask.height, t0, t1)) {
    return max_range;
  }
  Axis ax = start_axis(ox, ray.dx, t0, mask.width);
  Axis ay = start_axis(oy, ray.dy, t0, mask.height);
  // A ray entering the map (or starting) in a blocking cell stops where it enters: 0 for an
  // origin inside a wall.
  double t = t0;
  const double t_max = static_cast<double>(max_range) / mask.resolution;
  while (!mask.blocks(ax.cell, ay.cell)) {
    // Step across whichever boundary comes first; on a tie (the ray passes a corner) x goes
    // first, and the y step follows at the same t.
    Axis& a = ax.t_next <= ay.t_next ? ax : ay;
    t = a.t_next;
    a.cell += a.step;
    a.t_next += a.t_delta;
    if (t >= t_max) return max_range;
    if (ax.cell < 0 || ay.cell < 0 || ax.cell >= mask.width || ay.cell >= mask.height) {
      return max_range;  // left the map: nothing blocks off it
    }
  }
  return std::min(static_cast<float>(t * mask.resolution), max_range);
}

}  // namespace

GridRayCaster::GridRayCaster(const OccupancyGrid& grid, RayCastOptions options)
    : width_(grid.width()),
      height_(grid.height()),
      resolution_(grid.resolution()),
      origin_(grid.origin()),
      options_(options),
      blocking_(detail::blocking_mask(grid, options.unknown_blocks)) {}

void GridRayCaster::cast(const RayBatch& batch, std::span<float> ranges) const {
  const detail::GridFrame frame(origin_);
  const detail::BatchRays rays(frame, batch, ranges.size());
  const detail::CellMask mask{width_, height_, resolution_, blocking_.data()};
  const std::size_t beams = rays.beams();
  par::for_each_chunk(
      rays.particles(), options_.particle_grain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t p = begin; p < end; ++p) {
          const detail::SensorFrame s = rays.sensor(p);
          for (std::size_t b = 0; b < beams; ++b) {
            ranges[p * beams + b] = s.finite ? walk(mask, rays.ray(s, b), batch.max_range)
                                             : std::numeric_limits<float>::quiet_NaN();
          }
        }
      });
}

float GridRayCaster::cast_one(Point2 origin, double angle, float max_range) const {
  detail::check_max_range(max_range);
  const detail::GridRay ray = detail::GridFrame(origin_).ray(origin, angle);
  if (!std::isfinite(ray.ox) || !std::isfinite(ray.oy) || !std::isfinite(ray.dx)) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  const detail::CellMask mask{width_, height_, resolution_, blocking_.data()};
  return walk(mask, ray, max_range);
}

}  // namespace mote
