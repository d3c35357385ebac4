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
#include "wall_segments.hpp"

namespace mote {

namespace {

constexpr float kWallBottom = -1.0F;  ///< m, walls span z in [-1, 1]; rays travel at z = 0
constexpr float kWallTop = 1.0F;

/// The segment lengthened by kSnapDistance at both ends. Embree's watertight test leaves the
/// open end of a wall to edge tie-breaking, so a ray through a cell corner could pass or stop
/// depending on the triangle's orientation; the overlap makes it stop, as the grid walk does.
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

/// Height (m) of a wall triangle's far vertex, below the rays' plane z = 0. Close to 0 keeps the
/// triangle's bounding box within 1/64 of its segment's length; the triangle stays well shaped.
constexpr float kFarVertexZ = -1.0F / 64.0F;

/// Adds one triangle per wall segment to a fresh geometry attached to the scene. The triangle
/// stands in the wall's vertical plane with one edge upright at the segment's start (z in [-1, 1])
/// and its far vertex below z = 0, placed so that the edge from the top crosses z = 0 exactly at
/// the segment's end: the triangle's cut with the rays' plane is the segment. One triangle, not a
/// quad (two triangles), leaves no inner edge for a ray to slip through, so the scene can use
/// Embree's faster non-robust traversal; the ends overlap their neighbours (extended()).
void add_walls(RTCScene scene, const std::vector<detail::WallSegment>& walls) {
  RTCGeometry geometry = rtcNewGeometry(detail::embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * walls.size()));
  auto* triangles = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), walls.size()));
  if (vertices == nullptr || triangles == nullptr) {
    rtcReleaseGeometry(geometry);
    detail::check_embree("allocating the wall triangles");
    throw Error("Embree: allocating the wall triangles failed");
  }
  // The top edge falls from kWallTop to kFarVertexZ and crosses z = 0 at the fraction
  // kWallTop / (kWallTop - kFarVertexZ) of the way: the far vertex sits at `reach` times the
  // segment's length from its start.
  const float reach = 1.0F - kFarVertexZ / kWallTop;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const detail::WallSegment s = extended(walls[w]);
    const float far_x = s.x0 + reach * (s.x1 - s.x0);
    const float far_y = s.y0 + reach * (s.y1 - s.y0);
    const float corners[9] = {s.x0,     s.y0,  kWallBottom, s.x0,       s.y0,
                              kWallTop, far_x, far_y,       kFarVertexZ};
    for (std::size_t c = 0; c < 9; ++c) vertices[9 * w + c] = corners[c];
    for (unsigned c = 0; c < 3; ++c) triangles[3 * w + c] = static_cast<unsigned>(3 * w) + c;
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
    detail::check_embree("creating the wall scene");
    try {
      build(walls);
    } catch (...) {
      rtcReleaseScene(scene);  // the destructor does not run for a throwing constructor
      throw;
    }
  }
  void build(const std::vector<detail::WallSegment>& walls) {
    // No RTC_SCENE_FLAG_ROBUST: it cost 10-28% per ray, and it was only needed while each wall
    // was a quad whose two triangles met in the middle of the wall (see add_walls).
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
    detail::check_embree_thread("casting rays");
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
  detail::check_embree_thread("casting a ray");
  return range;
}

}  // namespace mote
