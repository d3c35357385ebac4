#pragma once
/// \file
/// The signed distance to the surface of the map's obstacles: positive in free and unknown space
/// (the distance to the nearest occupied cell), negative inside obstacles (the distance to the
/// nearest cell that is not occupied), zero on the boundary between an occupied cell and its
/// neighbour. A scan matched on it ends its readings on the surface of a wall drawn several cells
/// thick, where the unsigned field is zero across the whole wall and lets them sink into it.

#include <vector>

#include "mote/core/pose.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// Per-cell signed distance, m, with the grid's geometry; values at cell centres.
class SignedDistanceField {
 public:
  /// Two exact distance transforms (distance_field.hpp), out of and into the obstacles, each
  /// clamped at max_distance (m). A grid without obstacles is max_distance everywhere. Built in
  /// the caller's task arena. Throws ConfigError when max_distance is not positive.
  SignedDistanceField(const OccupancyGrid& grid, float max_distance);

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }  ///< lower-left corner
  [[nodiscard]] float max_distance() const noexcept { return max_distance_; }
  /// The value of cell (i, j) inside the grid, m.
  [[nodiscard]] float at(int i, int j) const noexcept {
    return values_[static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) +
                   static_cast<std::size_t>(i)];
  }

 private:
  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  float max_distance_;
  std::vector<float> values_;
};

}  // namespace mote
