#pragma once
// Walking a ray through the map on its distance field, in grid-frame cell units (no per-step
// frame change): the blocked-beam filter and the localization state's see-through test.
// Internal.

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "mote/core/pose.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/maps/signed_distance_field.hpp"

namespace mote {

// The distance field in cell units, walked in the grid frame (no per-step frame change).
class FieldWalker {
 public:
  FieldWalker(const OccupancyGrid& grid, const SignedDistanceField& field)
      : grid_(grid),
        field_(field),
        inv_cell_(1.0 / grid_.resolution()),
        width_(grid_.width()),
        height_(grid_.height()) {}

  // A map-frame point and direction in grid-frame cell units.
  [[nodiscard]] Point2 cell_point(Point2 world) const {
    const Point2 g = grid_.to_grid_frame(world);
    return {g.x * inv_cell_, g.y * inv_cell_};
  }
  [[nodiscard]] Point2 cell_direction(double ux, double uy) const {
    const Point2 o = grid_.to_grid_frame({0.0, 0.0});
    const Point2 e = grid_.to_grid_frame({ux, uy});
    return {e.x - o.x, e.y - o.y};
  }
  // Distance (cells) from the cell holding p to the nearest occupied cell centre, or -1 off
  // the map.
  [[nodiscard]] double cells_to_wall(Point2 p) const {
    const double fi = std::floor(p.x);
    const double fj = std::floor(p.y);
    if (!(fi >= 0.0 && fj >= 0.0 && fi < width_ && fj < height_)) return -1.0;
    const auto index = static_cast<std::size_t>(fj) * static_cast<std::size_t>(width_) +
                       static_cast<std::size_t>(fi);
    return field_.obstacle_distance(index) * inv_cell_;
  }
  // True when the map holds no obstacle on the ray p + t u for t in [from, to] (cells).
  // Sphere tracing: from any point the nearest occupied cell centre is d away, so the ray is
  // free for d less 1.5 cells (the point anywhere in its cell, the occupied cell's extent);
  // steps are at least half a cell. Off the map the ray is past every mapped wall: not free.
  [[nodiscard]] bool free(Point2 p, Point2 u, double from, double to) const {
    for (double t = from; t < to;) {
      const double d = cells_to_wall({p.x + t * u.x, p.y + t * u.y});
      if (d < 0.5) return false;  // an occupied cell, or off the map
      t += std::max(d - 1.5, 0.5);
    }
    return true;
  }
  // True when the ray p + t u runs into an occupied cell for some t in [from, to] (cells) at
  // 30 degrees or more to the wall, walked as free() walks it; the ray stops at the map's edge
  // (what lies beyond is unknown). A ray that only grazes a wall (its distance to the wall
  // falls by less than half the distance travelled over the last two cells, under 30 degrees)
  // is walked on through it: a reading along a wall drawn ragged clips its bumps, and a range
  // at such an angle is as uncertain as the wall's drawing.
  [[nodiscard]] bool runs_into_wall(Point2 p, Point2 u, double from, double to) const {
    constexpr double kLookBack = 2.0;  // cells
    for (double t = from; t < to;) {
      const double d = cells_to_wall({p.x + t * u.x, p.y + t * u.y});
      if (d < 0.0) return false;  // off the map
      if (d >= 0.5) {
        t += std::max(d - 1.5, 0.5);
        continue;
      }
      const double back = std::max(t - kLookBack, from);
      const double before = cells_to_wall({p.x + back * u.x, p.y + back * u.y});
      if (t - back > 0.0 && before - d >= 0.5 * (t - back)) return true;
      t += 0.5;
    }
    return false;
  }
  [[nodiscard]] double inv_cell() const { return inv_cell_; }

 private:
  const OccupancyGrid& grid_;
  const SignedDistanceField& field_;  // its obstacle_distance()
  double inv_cell_;
  double width_;
  double height_;
};

}  // namespace mote
