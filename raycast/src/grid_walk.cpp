#include "grid_walk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mote::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Clips the ray parameter interval [t0, t1] (m) to the slab [lo, hi] along one axis; false
/// when the ray never meets it.
bool clip_axis(double o, double d, double lo, double hi, double& t0, double& t1) {
  if (d == 0.0) return o >= lo && o <= hi;
  double enter = (lo - o) / d;
  double leave = (hi - o) / d;
  if (enter > leave) std::swap(enter, leave);
  t0 = std::max(t0, enter);
  t1 = std::min(t1, leave);
  return t0 <= t1;
}

/// The grid lines one axis of the ray crosses, in order (Amanatides-Woo's tMax): the cell the
/// ray is in along this axis, the next line and the ray parameter (m) where it is crossed,
/// taken from the float lattice so the walk meets exactly the lines Embree's walls stand on.
struct LineCursor {
  int cell = 0;
  int line = 0;
  int step = 0;
  double t = kInf;
  double inv = 0.0;  ///< 1 / direction component

  LineCursor(const CellMask& m, double o, double d, double t0, int count) {
    const double p = o + t0 * d;
    cell = m.cell_of(p, count);
    if (d == 0.0) return;
    step = d > 0.0 ? 1 : -1;
    inv = 1.0 / d;
    line = d > 0.0 ? cell + 1 : cell;
    t = (m.line(line) - o) * inv;
  }
  void advance(const CellMask& m, double o, int count) {
    cell += step;
    line += step;
    t = line < 0 || line > count ? kInf : (m.line(line) - o) * inv;
  }
};

/// Whether a wall covers point `along` (m) of grid line `line`, the ray being in cell `cell`
/// along the line. Walls are the boundaries between cells whose states differ, extended by
/// kSnapDistance past their ends as Embree's walls are, so touching a wall's end (a cell
/// corner) counts as a hit. `differs(line, cell)` says whether the two cells beside `line` at
/// position `cell` differ.
template <class Differs>
bool wall_at(const CellMask& m, int line, double along, int cell, const Differs& differs) {
  return differs(line, cell) ||
         (along - m.line(cell) <= kSnapDistance && differs(line, cell - 1)) ||
         (m.line(cell + 1) - along <= kSnapDistance && differs(line, cell + 1));
}

}  // namespace

float walk_grid(const CellMask& m, const GridRay& r, float max_range) {
  double t0 = 0.0;
  double t1 = max_range;
  const double e = kSnapDistance;
  if (!clip_axis(r.ox, r.dx, -e, m.line(m.width) + e, t0, t1) ||
      !clip_axis(r.oy, r.dy, -e, m.line(m.height) + e, t0, t1)) {
    return max_range;
  }
  const auto column_differs = [&m](int line, int row) {
    return m.blocks_or_free(line - 1, row) != m.blocks_or_free(line, row);
  };
  const auto row_differs = [&m](int line, int column) {
    return m.blocks_or_free(column, line - 1) != m.blocks_or_free(column, line);
  };
  LineCursor x(m, r.ox, r.dx, t0, m.width);
  LineCursor y(m, r.oy, r.dy, t0, m.height);
  // Visit the crossings in order of t; a ray along a grid line never crosses it, so the walls
  // lying in its own line are skipped, as Embree skips walls the ray lies in.
  while (true) {
    const double t = std::min(x.t, y.t);
    if (t > t1) return max_range;
    if (x.t <= y.t) {
      if (wall_at(m, x.line, r.oy + t * r.dy, y.cell, column_differs)) return static_cast<float>(t);
      x.advance(m, r.ox, m.width);
    } else {
      if (wall_at(m, y.line, r.ox + t * r.dx, x.cell, row_differs)) {
        return static_cast<float>(t);
      }
      y.advance(m, r.oy, m.height);
    }
  }
}

}  // namespace mote::detail
