#pragma once
/// \file
/// Where a robot can be: the interface through which the engine draws uniform poses in free
/// space (global initialization, recovery injection) without depending on how a map stores it.
/// mote::maps implements it for occupancy grids.

#include <cstddef>

namespace mote {

/// A point in the map frame, m.
struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

/// An axis-aligned box in the map frame, m.
struct Bounds2 {
  double min_x = 0.0;
  double min_y = 0.0;
  double max_x = 0.0;
  double max_y = 0.0;
};

/// The free part of a map, as a list of equally sized cells.
class FreeSpace {
 public:
  virtual ~FreeSpace() = default;

  /// Number of free cells; 0 means a map with nowhere to be.
  [[nodiscard]] virtual std::size_t free_cell_count() const noexcept = 0;

  /// The point at fractional position (u, v) in [0, 1)^2 of free cell k (k < free_cell_count()),
  /// in the map frame. Uniform (u, v) give a point uniform over the cell.
  [[nodiscard]] virtual Point2 free_point(std::size_t k, double u, double v) const noexcept = 0;

  /// The map frame box holding every cell of the map (free or not).
  [[nodiscard]] virtual Bounds2 bounds() const noexcept = 0;
};

}  // namespace mote
