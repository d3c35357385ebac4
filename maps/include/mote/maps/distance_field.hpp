#pragma once
/// \file
/// Exact Euclidean distance transform of an occupancy grid (Felzenszwalb and Huttenlocher,
/// "Distance Transforms of Sampled Functions", Theory of Computing 8, 2012): the distance from
/// every cell centre to the nearest obstacle cell centre, in linear time, columns then rows.

#include <limits>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// What counts as an obstacle and where distances stop.
struct DistanceFieldOptions {
  /// Treat unknown cells as obstacles too (amcl's likelihood field does not).
  bool unknown_is_obstacle = false;
  /// Distances above this are stored as this value, m; +inf keeps them all exact.
  float max_distance = std::numeric_limits<float>::infinity();
};

/// Per-cell distance to the nearest obstacle, m, with the grid's geometry. A grid without any
/// obstacle gives +inf (or max_distance) everywhere. Built in parallel in the caller's task
/// arena; the result does not depend on the thread count.
class DistanceField {
 public:
  /// Throws ConfigError when max_distance is NaN or negative.
  explicit DistanceField(const OccupancyGrid& grid, DistanceFieldOptions options = {});

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }  ///< m per cell
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }    ///< lower-left corner
  [[nodiscard]] const DistanceFieldOptions& options() const noexcept { return options_; }

  /// Distance of a cell inside the grid, m.
  [[nodiscard]] float at(CellIndex c) const noexcept {
    return distances_[static_cast<std::size_t>(c.j) * static_cast<std::size_t>(width_) +
                      static_cast<std::size_t>(c.i)];
  }
  /// Every distance, m, row-major from the bottom row like OccupancyGrid::cells().
  [[nodiscard]] const std::vector<float>& distances() const noexcept { return distances_; }

 private:
  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  DistanceFieldOptions options_;
  std::vector<float> distances_;
};

}  // namespace mote
