#include "grid_walk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mote::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Clips the ray parameter interval [t0, t1] (m) to the slab [0, size] along one axis; false
/// when the ray never meets it.
bool clip_axis(double o, double d, double size, double& t0, double& t1) {
  if (d == 0.0) return o >= 0.0 && o <= size;
  double enter = (0.0 - o) / d;
  double leave = (size - o) / d;
  if (enter > leave) std::swap(enter, leave);
  t0 = std::max(t0, enter);
  t1 = std::min(t1, leave);
  return t0 <= t1;
}

/// One axis of the Amanatides-Woo walk: current cell, step and the ray parameter (m) at which
/// the ray crosses the next grid line, taken from the float lattice so it meets the same
/// lines as Embree's walls.
struct Axis {
  int cell = 0;
  int step = 0;
  double t_next = kInf;

  void advance(const CellMask& m, double o, double d) {
    cell += step;
    t_next = (m.line(cell + (step > 0 ? 1 : 0)) - o) / d;
  }
};

Axis start_axis(const CellMask& m, double o, double d, double t0, int count) {
  Axis a;
  a.cell = std::clamp(m.cell_of(o + t0 * d, count), 0, count - 1);
  if (d == 0.0) return a;
  a.step = d > 0.0 ? 1 : -1;
  a.t_next = (m.line(a.cell + (d > 0.0 ? 1 : 0)) - o) / d;
  return a;
}

/// A ray lying exactly on grid line `across` (a row line when horizontal): it touches the
/// cells on both sides, so it stops at the first crossing line where either side changes.
template <class State>
double walk_line(const CellMask& m, double o, double d, int across, int count, double t1,
                 const State& state) {
  const int first = d > 0.0 ? m.cell_of(o, count) + 1 : m.cell_of(o, count);
  const int step = d > 0.0 ? 1 : -1;
  for (int k = std::clamp(first, 0, count); k >= 0 && k <= count; k += step) {
    const double t = (m.line(k) - o) / d;
    if (t > t1) break;
    const bool below = state(k - 1, across - 1) != state(k, across - 1);
    const bool above = state(k - 1, across) != state(k, across);
    if (t >= 0.0 && (below || above)) return t;
  }
  return kInf;
}

/// The general walk, touching cells at exact corner crossings.
double walk_cells(const CellMask& m, const GridRay& r, double t0, double t1) {
  Axis ax = start_axis(m, r.ox, r.dx, t0, m.width);
  Axis ay = start_axis(m, r.oy, r.dy, t0, m.height);
  if (m.blocks(ax.cell, ay.cell)) return t0;  // starts (or enters the map) inside a wall
  while (true) {
    const double t = std::min(ax.t_next, ay.t_next);
    if (t > t1) return kInf;
    bool hit = false;
    if (ax.t_next == ay.t_next) {
      hit = m.blocks_or_free(ax.cell + ax.step, ay.cell) ||
            m.blocks_or_free(ax.cell, ay.cell + ay.step);
      ax.advance(m, r.ox, r.dx);
      ay.advance(m, r.oy, r.dy);
    } else if (ax.t_next < ay.t_next) {
      ax.advance(m, r.ox, r.dx);
    } else {
      ay.advance(m, r.oy, r.dy);
    }
    if (hit || m.blocks_or_free(ax.cell, ay.cell)) return t;
  }
}

}  // namespace

float walk_grid(const CellMask& m, const GridRay& r, float max_range) {
  double t0 = 0.0;
  double t1 = max_range;
  if (!clip_axis(r.ox, r.dx, m.line(m.width), t0, t1) ||
      !clip_axis(r.oy, r.dy, m.line(m.height), t0, t1)) {
    return max_range;
  }
  double t = kInf;
  const int row = m.cell_of(r.oy, m.height);
  const int col = m.cell_of(r.ox, m.width);
  if (r.dy == 0.0 && m.line(row) == r.oy) {
    t = walk_line(m, r.ox, r.dx, row, m.width, t1,
                  [&m](int a, int b) { return m.blocks_or_free(a, b); });
  } else if (r.dx == 0.0 && m.line(col) == r.ox) {
    t = walk_line(m, r.oy, r.dy, col, m.height, t1,
                  [&m](int a, int b) { return m.blocks_or_free(b, a); });
  } else {
    t = walk_cells(m, r, t0, t1);
  }
  return t < static_cast<double>(max_range) ? static_cast<float>(t) : max_range;
}

}  // namespace mote::detail
