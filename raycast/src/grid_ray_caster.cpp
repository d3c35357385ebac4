#include "mote/raycast/grid_ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "grid_walk.hpp"
#include "mote/core/parallel.hpp"
#include "ray_setup.hpp"

namespace mote {

namespace {

/// The shared start rule, then the walk: a sensor inside a blocking cell reads 0.
float cast_ray(const detail::CellMask& mask, const detail::GridRay& grid_ray, float max_range) {
  const detail::GridRay ray = mask.prepare(grid_ray);
  if (mask.blocks_start(ray.ox, ray.oy)) return 0.0F;
  return detail::walk_grid(mask, ray, max_range);
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
  const detail::CellMask mask{width_, height_, static_cast<float>(resolution_), blocking_.data()};
  const detail::BatchRays rays(frame, mask, batch, ranges.size());
  const std::size_t beams = rays.beams();
  par::for_each_chunk(
      rays.particles(), options_.particle_grain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t p = begin; p < end; ++p) {
          const detail::SensorFrame s = rays.sensor(p);
          for (std::size_t b = 0; b < beams; ++b) {
            ranges[p * beams + b] = s.finite ? cast_ray(mask, rays.ray(s, b), batch.max_range)
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
  const detail::CellMask mask{width_, height_, static_cast<float>(resolution_), blocking_.data()};
  return cast_ray(mask, ray, max_range);
}

}  // namespace mote
