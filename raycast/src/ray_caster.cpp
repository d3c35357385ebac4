#include "mote/raycast/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "embree_device.hpp"
#include "embree_packets.hpp"
#include "mote/core/parallel.hpp"
#include "ray_setup.hpp"
#include "wall_segments.hpp"

namespace mote {

namespace {

constexpr float kWallBottom = -1.0F;  ///< m, walls span z in [-1, 1]; rays travel at z = 0
constexpr float kWallTop = 1.0F;

/// The segment lengthened by kSnapDistance at both ends. Embree's watertight test leaves the
/// open end of a wall to edge tie-breaking, so a ray through a cell corner could pass or stop
/// depending on the quad's orientation; the overlap makes it stop, as the grid walk does.
detail::WallSegment extended(detail::WallSegment s) {
  const auto e = static_cast<float>(detail::kSnapDistance);
  if (s.y0 == s.y1) {
    s.x0 -= e;
    s.x1 += e;
  } else {
    s.y0 -= e;
    s.y1 += e;
  }
  return s;
}

/// Adds one quad per wall segment, extruded in z, to a fresh geometry attached to the scene.
void add_walls(RTCScene scene, const std::vector<detail::WallSegment>& walls) {
  RTCGeometry geometry = rtcNewGeometry(detail::embree_device(), RTC_GEOMETRY_TYPE_QUAD);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * walls.size()));
  auto* quads = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), walls.size()));
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const detail::WallSegment s = extended(walls[w]);
    const float corners[12] = {s.x0, s.y0, kWallBottom, s.x1, s.y1, kWallBottom,
                               s.x1, s.y1, kWallTop,    s.x0, s.y0, kWallTop};
    for (std::size_t c = 0; c < 12; ++c) vertices[12 * w + c] = corners[c];
    for (unsigned c = 0; c < 4; ++c) quads[4 * w + c] = static_cast<unsigned>(4 * w) + c;
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);  // the scene holds its own reference
}

}  // namespace

struct RayCaster::Impl {
  detail::GridFrame frame;
  RayCastOptions options;
  std::vector<std::uint8_t> blocking;
  detail::CellMask mask;
  std::size_t wall_count = 0;
  RTCScene scene = nullptr;

  Impl(const OccupancyGrid& grid, RayCastOptions opts)
      : frame(grid.origin()),
        options(opts),
        blocking(detail::blocking_mask(grid, opts.unknown_blocks)),
        mask{grid.width(), grid.height(), static_cast<float>(grid.resolution()), blocking.data()} {
    const std::vector<detail::WallSegment> walls = detail::wall_segments(mask);
    wall_count = walls.size();
    scene = rtcNewScene(detail::embree_device());
    // Robust mode makes the quads watertight, so rays through the shared corner of two walls
    // cannot slip between them.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    if (!walls.empty()) add_walls(scene, walls);
    rtcCommitScene(scene);
    detail::check_embree("building the wall scene");
  }
  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  /// Casts particles [begin, end) with the given query type; a sensor inside a blocking cell
  /// gets 0 on every beam, because Embree would report the wall's far side.
  template <class Query>
  void cast_chunk(const detail::BatchRays& rays, std::size_t begin, std::size_t end,
                  std::span<float> ranges) const {
    const detail::FlushDenormals denormals_off;
    const std::size_t beams = rays.beams();
    Query query(scene, rays.max_range(), ranges);
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
  }
};

RayCaster::RayCaster(const OccupancyGrid& grid, RayCastOptions options)
    : impl_(std::make_unique<Impl>(grid, options)) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

std::size_t RayCaster::wall_count() const noexcept { return impl_->wall_count; }

void RayCaster::cast(const RayBatch& batch, std::span<float> ranges) const {
  const detail::BatchRays rays(impl_->frame, impl_->mask, batch, ranges.size());
  const Impl& impl = *impl_;
  par::for_each_chunk(rays.particles(), impl.options.particle_grain,
                      [&](std::size_t begin, std::size_t end) {
                        if (impl.options.packets) {
                          impl.cast_chunk<detail::Packet16>(rays, begin, end, ranges);
                        } else {
                          impl.cast_chunk<detail::Single1>(rays, begin, end, ranges);
                        }
                      });
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
  detail::Single1 query(impl_->scene, max_range, std::span<float>(&range, 1));
  query.add(ray, 0);
  return range;
}

}  // namespace mote
