#pragma once
/// \file
/// The exact cell walk (Amanatides and Woo, "A Fast Voxel Traversal Algorithm", 1987): visits
/// every cell a ray crosses in order. Slower than Embree (design.md section 4: 225-340 ns per ray
/// per core) and simple enough to trust, so it is the oracle for tests and the benchmark baseline.

#include <cstdint>
#include <span>
#include <vector>

#include "mote/maps/occupancy_grid.hpp"
#include "mote/raycast/ray_batch.hpp"

namespace mote {

/// Grid-walk ray caster with the same contract as RayCaster (options.packets is ignored).
class GridRayCaster {
 public:
  /// Copies the blocking state of every cell.
  explicit GridRayCaster(const OccupancyGrid& grid, RayCastOptions options = {});

  /// Fills ranges[p * beams + b] (m), parallel over particles; same contract as RayCaster::cast.
  void cast(const RayBatch& batch, std::span<float> ranges) const;

  /// Range (m) from a map frame point along a map frame angle (rad), at most max_range.
  [[nodiscard]] float cast_one(Point2 origin, double angle, float max_range) const;

 private:
  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  RayCastOptions options_;
  std::vector<std::uint8_t> blocking_;  ///< 1 per blocking cell, row-major from the bottom
};

static_assert(RayCasterLike<GridRayCaster>);

}  // namespace mote
