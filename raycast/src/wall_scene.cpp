#include "wall_scene.hpp"

#include <vector>

#include "mote/core/error.hpp"
#include "wall_segments.hpp"

namespace mote::detail {

namespace {

constexpr float kWallBottom = -1.0F;  ///< m, walls span z in [-1, 1]; rays travel at z = 0
constexpr float kWallTop = 1.0F;

/// The segment lengthened by kSnapDistance at both ends. Embree's watertight test leaves the
/// open end of a wall to edge tie-breaking, so a ray through a cell corner could pass or stop
/// depending on the triangle's orientation; the overlap makes it stop, as the grid walk does.
WallSegment extended(WallSegment s) {
  const auto e = static_cast<float>(kSnapDistance);
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
void add_walls(RTCScene scene, const std::vector<WallSegment>& walls) {
  RTCGeometry geometry = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * walls.size()));
  auto* triangles = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), walls.size()));
  if (vertices == nullptr || triangles == nullptr) {
    rtcReleaseGeometry(geometry);
    check_embree("allocating the wall triangles");
    throw Error("Embree: allocating the wall triangles failed");
  }
  // The top edge falls from kWallTop to kFarVertexZ and crosses z = 0 at the fraction
  // kWallTop / (kWallTop - kFarVertexZ) of the way: the far vertex sits at `reach` times the
  // segment's length from its start.
  const float reach = 1.0F - kFarVertexZ / kWallTop;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const WallSegment s = extended(walls[w]);
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

WallScene::WallScene(const CellMask& mask) {
  const std::vector<WallSegment> walls = wall_segments(mask);
  wall_count_ = walls.size();
  scene_ = rtcNewScene(embree_device());
  check_embree("creating the wall scene");
  try {
    // No RTC_SCENE_FLAG_ROBUST: it cost 10-28% per ray, and it was only needed while each wall
    // was a quad whose two triangles met in the middle of the wall (see add_walls).
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    if (!walls.empty()) add_walls(scene_, walls);
    rtcCommitScene(scene_);
    check_embree("building the wall scene");
  } catch (...) {
    rtcReleaseScene(scene_);  // the destructor does not run for a throwing constructor
    throw;
  }
}

WallScene::~WallScene() {
  if (scene_ != nullptr) rtcReleaseScene(scene_);
}

std::size_t WallScene::bytes() const noexcept { return wall_scene_bytes(wall_count_); }

std::size_t wall_scene_bytes(std::size_t walls) noexcept {
  // 3 vertices of 12 bytes and 3 indices of 4 per triangle; a BVH4 node is 128 bytes, at most
  // one per two triangles in a leaf-of-one build, plus Embree's own triangle copy (64 bytes).
  return walls * (36 + 12 + 64 + 128);
}

}  // namespace mote::detail
