#pragma once
/// \file
/// The signed distance to the surface of the map's obstacles: positive in free and unknown space
/// (the distance to the nearest occupied cell), negative inside obstacles (the distance to the
/// nearest cell that is not occupied), zero on the boundary between an occupied cell and its
/// neighbour. A scan matched on it ends its readings on the surface of a wall drawn several cells
/// thick, where the unsigned field is zero across the whole wall and lets them sink into it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// Per-cell signed distance, m, with the grid's geometry; values at cell centres. Also holds the
/// unsigned distance to the nearest occupied cell centre (obstacle_distance), which is the same
/// transform out of the obstacles.
class SignedDistanceField {
 public:
  /// Two exact distance transforms (squared_distances.hpp), out of and into the obstacles, each
  /// clamped at max_distance (m). A grid without obstacles is max_distance everywhere. Built in
  /// the caller's task arena. Throws ConfigError when max_distance is not positive. Up to 181
  /// cells of max_distance (plus half a cell) it keeps 2 bytes per cell (a code into a table of
  /// the few thousand values a cell can hold); beyond that 8 bytes per cell (two floats).
  SignedDistanceField(const OccupancyGrid& grid, float max_distance);

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }  ///< lower-left corner
  [[nodiscard]] float max_distance() const noexcept { return max_distance_; }
  /// The value of cell (i, j) inside the grid, m.
  [[nodiscard]] float at(int i, int j) const noexcept {
    const std::size_t k = index(i, j);
    return codes_ ? signed_of_[codes_[k]] : values_[k];
  }
  /// The distance from the centre of the cell of row-major index k to the nearest occupied
  /// cell centre, m, clamped at max_distance: 0 in an occupied cell (DistanceField's value with
  /// unknown cells not obstacles).
  [[nodiscard]] float obstacle_distance(std::size_t k) const noexcept {
    return codes_ ? unsigned_of_[codes_[k]] : unsigned_[k];
  }

 private:
  [[nodiscard]] std::size_t index(int i, int j) const noexcept {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(i);
  }
  void build_codes(const OccupancyGrid& grid, int saturation);
  void build_floats(const OccupancyGrid& grid);

  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  float max_distance_;
  // Compact form: per cell a code, the squared distance out of the obstacles (free and unknown
  // cells) or cap + 1 + the squared distance into them (occupied cells); per code its values.
  std::unique_ptr<std::uint16_t[]> codes_;
  std::vector<float> signed_of_;
  std::vector<float> unsigned_of_;
  // Wide form, for clamps past 181 cells: the values themselves.
  std::vector<float> values_;
  std::vector<float> unsigned_;
};

}  // namespace mote
