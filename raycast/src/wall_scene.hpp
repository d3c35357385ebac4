#pragma once
/// \file
/// Internal: the Embree scene of a grid's walls, shared by the exact caster (RayCaster) and the
/// range table, which casts the rays its entries cannot vouch for exactly.

#include <cstddef>

#include "embree_device.hpp"
#include "ray_setup.hpp"

namespace mote::detail {

/// One triangle per maximal wall segment of the mask (wall_segments()), committed and ready for
/// queries. Throws mote::Error when Embree fails.
class WallScene {
 public:
  explicit WallScene(const CellMask& mask);
  ~WallScene();
  WallScene(const WallScene&) = delete;
  WallScene& operator=(const WallScene&) = delete;

  [[nodiscard]] RTCScene scene() const noexcept { return scene_; }
  [[nodiscard]] std::size_t wall_count() const noexcept { return wall_count_; }
  /// An upper estimate of the bytes Embree keeps for the scene: the vertex and index buffers
  /// and a BVH of at most two nodes per triangle (Embree reports no figure of its own).
  [[nodiscard]] std::size_t bytes() const noexcept;

 private:
  RTCScene scene_ = nullptr;
  std::size_t wall_count_ = 0;
};

/// The estimate WallScene::bytes gives for a scene of `walls` triangles.
[[nodiscard]] std::size_t wall_scene_bytes(std::size_t walls) noexcept;

}  // namespace mote::detail
