#pragma once
/// \file
/// The exact Euclidean distance transform in two bytes per cell: the squared distance in cells
/// from every cell centre to the nearest obstacle cell centre, an integer, saturated where the
/// distance passes a clamp. Every value a DistanceField with that clamp holds is a function of
/// this integer, so a table over the few hundred integers below the clamp gives the same floats
/// bit for bit, in half the memory, and anything computed per distance (a log-likelihood) is
/// computed once per integer instead of once per cell.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "mote/core/pose.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// Which cells a transform measures to.
enum class ObstacleCells : std::uint8_t {
  kOccupied,           ///< occupied cells (unknown cells are not obstacles, as in amcl)
  kOccupiedOrUnknown,  ///< occupied and unknown cells
  kSurface,            ///< occupied cells with a free 4-neighbour (off the grid is occupied)
  kNotOccupied,        ///< free and unknown cells: the depth of a cell inside an obstacle
};

/// Squared distances in cells, each min(exact, cap()), 2 bytes per cell. Built in parallel in the
/// caller's task arena (rows after columns, every line independent: Felzenszwalb and
/// Huttenlocher 2012, section 2.1); the result does not depend on the thread count.
class SquaredDistances {
 public:
  /// The largest saturation, in cells, that 16 bits hold (cap() = 255^2).
  static constexpr int kMaxSaturation = 255;

  /// The saturation in cells for a clamp: the smallest n with float(n * resolution) >= clamp,
  /// so that every squared distance >= n^2 gives the clamp; 0 when the clamp is not finite or
  /// needs more than max_cells.
  [[nodiscard]] static int saturation(double resolution, float clamp, int max_cells);

  /// Throws ConfigError unless saturation(resolution, clamp, kMaxSaturation) > 0 (a positive,
  /// finite clamp of at most 255 cells).
  SquaredDistances(const OccupancyGrid& grid, ObstacleCells obstacles, float clamp);

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }  ///< m per cell
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }    ///< lower-left corner
  [[nodiscard]] float clamp() const noexcept { return clamp_; }             ///< m
  /// Saturation of the squared distances, cells^2: a value of cap() means "at least the clamp".
  [[nodiscard]] std::uint32_t cap() const noexcept { return cap_; }
  /// Row-major from the bottom row like OccupancyGrid::cells().
  [[nodiscard]] const std::uint16_t* data() const noexcept { return squared_.get(); }
  [[nodiscard]] std::uint16_t at(std::size_t k) const noexcept { return squared_[k]; }
  /// The distance, m, of a squared distance s <= cap(): min(float(sqrt(s) * resolution), clamp),
  /// the value DistanceField computes.
  [[nodiscard]] float distance(std::uint32_t s) const noexcept;

 private:
  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  float clamp_;
  std::uint32_t cap_;
  std::unique_ptr<std::uint16_t[]> squared_;
};

/// Receives cells [i0, i0 + count) of grid row j: their squared distances s[0 .. count).
using SquaredRowPiece =
    std::function<void(std::size_t j, std::size_t i0, std::size_t count, const std::uint16_t* s)>;

/// The transform a piece of a row at a time, for building a table of another type without a
/// full-size intermediate: calls piece(j, i0, count, s) once for every cell (in parallel, in
/// any order), each value min(exact, saturation^2). Up to 127 cells of
/// saturation it never holds more than a band of rows per thread: the distance along each row
/// first, then along the columns the minimum of d^2 + h(j + d)^2 over |d| < saturation, as
/// vector passes over whole rows (the transform separates in either order; Felzenszwalb and
/// Huttenlocher 2012, section 2). Beyond that a full-size array and the envelope along rows.
/// 1 <= saturation <= SquaredDistances::kMaxSaturation.
void for_each_squared_row(const OccupancyGrid& grid, ObstacleCells obstacles, int saturation,
                          const SquaredRowPiece& piece);

}  // namespace mote
