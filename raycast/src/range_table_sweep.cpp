#include "range_table_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mote::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The parallel lines of one direction: line l holds the points s_l * n + u * d, with
/// s_l = s_min + l * spacing and n = (-dy, dx) the normal.
struct LineFamily {
  double dx = 1.0;
  double dy = 0.0;
  double s_min = 0.0;
  double spacing = 0.5;
  int count = 0;
};

LineFamily family_for(int width, int height, double dx, double dy, double spacing) {
  const double w = width;
  const double h = height;
  // The normal offsets of the map's corners bound the lines that cross it.
  const double s0 = 0.0;
  const double s1 = -dy * w;
  const double s2 = dx * h;
  const double s3 = -dy * w + dx * h;
  const double lo = std::min({s0, s1, s2, s3});
  const double hi = std::max({s0, s1, s2, s3});
  return {dx, dy, lo, spacing, static_cast<int>(std::floor((hi - lo) / spacing)) + 2};
}

/// Sorts the points onto their nearest lines (a counting sort: stable in slot order), over the
/// lines [s.first_line, s.first_line + s.line_start.size() - 1) that hold points only.
void bucket_points(const LineFamily& f, std::span<const float> px, std::span<const float> py,
                   SweepScratch& s) {
  const std::size_t n = px.size();
  s.line_of.resize(n);
  s.along.resize(n);
  const double inv = 1.0 / f.spacing;
  int lo = f.count;
  int hi = -1;
  for (std::size_t p = 0; p < n; ++p) {
    const double x = px[p];
    const double y = py[p];
    // Offsets are >= s_min, so truncation rounds to nearest here.
    const int l = static_cast<int>((-f.dy * x + f.dx * y - f.s_min) * inv + 0.5);
    s.line_of[p] = l;
    s.along[p] = f.dx * x + f.dy * y;
    lo = std::min(lo, l);
    hi = std::max(hi, l);
  }
  s.first_line = n == 0 ? 0 : lo;
  s.line_start.assign(n == 0 ? 1 : static_cast<std::size_t>(hi - lo) + 2, 0);
  for (std::size_t p = 0; p < n; ++p) {
    ++s.line_start[static_cast<std::size_t>(s.line_of[p] - s.first_line) + 1];
  }
  for (std::size_t l = 1; l < s.line_start.size(); ++l) s.line_start[l] += s.line_start[l - 1];
  s.order.resize(n);
  std::vector<std::uint32_t> fill(s.line_start.begin(), s.line_start.end() - 1);
  for (std::size_t p = 0; p < n; ++p) {
    s.order[fill[static_cast<std::size_t>(s.line_of[p] - s.first_line)]++] =
        static_cast<std::uint32_t>(p);
  }
}

/// Walks line l from u_first (a point of the line inside the map) and records in `hits` where it
/// enters blocking cells, until the first entry beyond u_last or the map's edge.
void walk_line(const CellMask& mask, const LineFamily& f, int l, double u_first, double u_last,
               std::vector<double>& hits) {
  hits.clear();
  const double s = f.s_min + l * f.spacing;
  const double ox = -f.dy * s;  // the line's point at u = 0
  const double oy = f.dx * s;
  int i = std::clamp(static_cast<int>(std::floor(ox + u_first * f.dx)), 0, mask.width - 1);
  int j = std::clamp(static_cast<int>(std::floor(oy + u_first * f.dy)), 0, mask.height - 1);
  const int step_i = f.dx > 0.0 ? 1 : -1;
  const int step_j = f.dy > 0.0 ? 1 : -1;
  const long step_row = step_j * static_cast<long>(mask.width);
  double next_x = f.dx == 0.0 ? kInf : ((i + (f.dx > 0.0 ? 1 : 0)) - ox) / f.dx;
  double next_y = f.dy == 0.0 ? kInf : ((j + (f.dy > 0.0 ? 1 : 0)) - oy) / f.dy;
  const double delta_x = f.dx == 0.0 ? kInf : 1.0 / std::abs(f.dx);
  const double delta_y = f.dy == 0.0 ? kInf : 1.0 / std::abs(f.dy);
  long cell = static_cast<long>(j) * mask.width + i;  // index, stepped with i and j
  bool inside_wall = mask.cells[cell] != 0;           // the first point's cell is free, but be safe
  double u = u_first;
  while (true) {
    const bool blocking = mask.cells[cell] != 0;
    if (blocking && !inside_wall) {
      hits.push_back(u);
      if (u > u_last) return;
    }
    inside_wall = blocking;
    // Branch-free step to the nearer grid line: which axis comes next is data-dependent and
    // mispredicts about every other step on diagonal lines.
    const bool along_x = next_x < next_y;
    u = along_x ? next_x : next_y;
    next_x += along_x ? delta_x : 0.0;
    next_y += along_x ? 0.0 : delta_y;
    i += along_x ? step_i : 0;
    j += along_x ? 0 : step_j;
    cell += along_x ? step_i : step_row;
    if (static_cast<unsigned>(i) >= static_cast<unsigned>(mask.width) ||
        static_cast<unsigned>(j) >= static_cast<unsigned>(mask.height)) {
      return;
    }
  }
}

std::uint16_t encode(double range_cells, double units_per_cell) {
  const double v = std::floor(std::max(range_cells, 0.0) * units_per_cell + 0.5);
  return static_cast<std::uint16_t>(std::min(v, static_cast<double>(kNoHit - 1)));
}

}  // namespace

void sweep_direction(const CellMask& mask, std::span<const float> px, std::span<const float> py,
                     double lattice, double dx, double dy, double units_per_cell,
                     SweepScratch& scratch, std::span<std::uint16_t> column) {
  const LineFamily f = family_for(mask.width, mask.height, dx, dy, kLineSpacing * lattice);
  bucket_points(f, px, py, scratch);
  for (std::size_t line = 0; line + 1 < scratch.line_start.size(); ++line) {
    const int l = scratch.first_line + static_cast<int>(line);
    const std::uint32_t begin = scratch.line_start[line];
    const std::uint32_t end = scratch.line_start[line + 1];
    if (begin == end) continue;
    double u_first = kInf;
    double u_last = -kInf;
    for (std::uint32_t k = begin; k < end; ++k) {
      const double u = scratch.along[scratch.order[k]];
      u_first = std::min(u_first, u);
      u_last = std::max(u_last, u);
    }
    walk_line(mask, f, l, u_first, u_last, scratch.hits);
    const std::vector<double>& hits = scratch.hits;
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t slot = scratch.order[k];
      const double u = scratch.along[slot];
      const auto h = std::upper_bound(hits.begin(), hits.end(), u);
      column[slot] = h == hits.end() ? kNoHit : encode(*h - u, units_per_cell);
    }
  }
}

}  // namespace mote::detail
