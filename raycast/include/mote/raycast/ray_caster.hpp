#pragma once
/// \file
/// Ray casting on an occupancy grid with Embree: the grid's wall boundaries become merged segments,
/// rays go out in 16-wide packets (design.md section 4: 130-160 ns per ray per core).

#include <memory>
#include <span>

#include "mote/maps/occupancy_grid.hpp"
#include "mote/raycast/ray_batch.hpp"

namespace mote {

/// Casts rays against the blocking cells of a grid (occupied, and unknown unless
/// options.unknown_blocks is false). Off-map space is free: rays from outside travel until they
/// hit a wall or max_range. A ray that starts inside a blocking cell reports 0.
/// The caster copies what it needs: the grid may be destroyed afterwards. cast() is const and
/// thread-safe; it runs in the caller's task arena.
class RayCaster {
 public:
  /// Builds the Embree scene (one triangle per maximal wall segment). Throws mote::Error when
  /// Embree fails.
  explicit RayCaster(const OccupancyGrid& grid, RayCastOptions options = {});
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Fills ranges[p * beams + b] (m) for every particle p and beam b, parallel over particles.
  /// Throws ConfigError when the pose spans differ in length, ranges has the wrong size or
  /// max_range is not a positive number. Particles with a non-finite pose get NaN ranges.
  void cast(const RayBatch& batch, std::span<float> ranges) const;

  /// Range (m) from a map frame point along a map frame angle (rad), at most max_range.
  [[nodiscard]] float cast_one(Point2 origin, double angle, float max_range) const;

  /// Number of wall segments (triangles) in the scene.
  [[nodiscard]] std::size_t wall_count() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

static_assert(RayCasterLike<RayCaster>);

}  // namespace mote
