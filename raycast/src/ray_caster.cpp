#include "mote/raycast/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "embree_device.hpp"
#include "embree_packets.hpp"
#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "ray_setup.hpp"
#include "wall_scene.hpp"

namespace mote {

struct RayCaster::Impl {
  detail::GridFrame frame;
  RayCastOptions options;
  std::vector<std::uint8_t> blocking;
  detail::CellMask mask;
  detail::WallScene walls;

  Impl(const OccupancyGrid& grid, RayCastOptions opts)
      : frame(grid.origin()),
        options(opts),
        blocking(detail::blocking_mask(grid, opts.unknown_blocks)),
        mask{grid.width(), grid.height(), static_cast<float>(grid.resolution()), blocking.data()},
        walls(mask) {}

  /// Casts particles [begin, end) with the given query type; a sensor inside a blocking cell
  /// gets 0 on every beam, because Embree would report the wall's far side.
  template <class Query>
  void cast_chunk(const detail::BatchRays& rays, std::size_t begin, std::size_t end,
                  std::span<float> ranges) const {
    const detail::FlushDenormals denormals_off;
    const std::size_t beams = rays.beams();
    Query query(walls.scene(), rays.max_range(), ranges);
    for (std::size_t p = begin; p < end; ++p) {
      const detail::SensorFrame s = rays.sensor(p);
      const auto row = ranges.subspan(p * beams, beams);
      if (!s.finite) {
        std::fill(row.begin(), row.end(), std::numeric_limits<float>::quiet_NaN());
      } else if (mask.blocks_start(s.ox, s.oy)) {
        std::fill(row.begin(), row.end(), 0.0F);
      } else {
        for (std::size_t b = 0; b < beams; ++b) query.add(rays.ray(s, b), p * beams + b);
      }
    }
    query.flush();
    detail::check_embree_thread("casting rays");
  }

  /// Every particle through Embree, parallel over particles.
  void cast_embree(const detail::BatchRays& rays, std::span<float> ranges) const {
    par::for_each_chunk(rays.particles(), options.particle_grain,
                        [&](std::size_t begin, std::size_t end) {
                          if (options.packets) {
                            cast_chunk<detail::Packet16>(rays, begin, end, ranges);
                          } else {
                            cast_chunk<detail::Single1>(rays, begin, end, ranges);
                          }
                        });
  }
};

RayCaster::RayCaster(const OccupancyGrid& grid, RayCastOptions options)
    : impl_(std::make_unique<Impl>(grid, options)) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

std::size_t RayCaster::wall_count() const noexcept { return impl_->walls.wall_count(); }

void RayCaster::cast(const RayBatch& batch, std::span<float> ranges) const {
  const detail::BatchRays rays(impl_->frame, impl_->mask, batch, ranges.size());
  impl_->cast_embree(rays, ranges);
}

float RayCaster::cast_one(Point2 origin, double angle, float max_range) const {
  detail::check_max_range(max_range);
  const detail::GridRay ray = impl_->mask.prepare(impl_->frame.ray(origin, angle));
  if (!std::isfinite(ray.ox) || !std::isfinite(ray.oy) || !std::isfinite(ray.dx)) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  if (impl_->mask.blocks_start(ray.ox, ray.oy)) return 0.0F;
  const detail::FlushDenormals denormals_off;
  float range = max_range;
  detail::Single1 query(impl_->walls.scene(), max_range, std::span<float>(&range, 1));
  query.add(ray, 0);
  detail::check_embree_thread("casting a ray");
  return range;
}

}  // namespace mote
