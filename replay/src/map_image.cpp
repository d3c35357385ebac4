// map.png: grid cells to pixels, the trajectories, particles and markers, axes in metres, and
// the legend below (map_legend.cpp). Written by maps' write_png.
#include "mote/replay/map_image.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "map_legend.hpp"
#include "map_style.hpp"

namespace mote::replay {
namespace {

namespace style = map_style;
using figure::Rgb;

constexpr int kPad = 12;  // px, white border above and right of the map

// The cropped cell range [i0, i1] x [j0, j1] and the integer scale of each cell in pixels.
struct View {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  int scale = 1;
};

struct CellBox {
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  void add(double u, double v) {
    u0 = std::min(u0, u);
    u1 = std::max(u1, u);
    v0 = std::min(v0, v);
    v1 = std::max(v1, v);
  }
  [[nodiscard]] bool empty() const { return u0 > u1; }
};

// A map frame point in fractional cell units of the grid frame.
Point2 to_cells(const OccupancyGrid& map, const Pose2& p) {
  const Point2 g = map.to_grid_frame({p.x, p.y});
  return {g.x / map.resolution(), g.y / map.resolution()};
}

View choose_view(const OccupancyGrid& map, const MapOverlay& overlay, const MapRenderOptions& o) {
  CellBox box;
  for (const auto* path : {&overlay.reference, &overlay.estimate}) {
    for (const logs::StampedPose& s : *path) {
      const Point2 c = to_cells(map, s.pose);
      if (std::isfinite(c.x) && std::isfinite(c.y)) box.add(c.x, c.y);
    }
  }
  View v{0, map.width() - 1, 0, map.height() - 1, 1};
  if (!box.empty()) {
    const double m = o.margin_m / map.resolution();
    const auto clamp_to = [](double c, int hi) {
      return static_cast<int>(std::clamp(std::floor(c), 0.0, static_cast<double>(hi)));
    };
    v.i0 = clamp_to(box.u0 - m, map.width() - 1);
    v.i1 = clamp_to(box.u1 + m, map.width() - 1);
    v.j0 = clamp_to(box.v0 - m, map.height() - 1);
    v.j1 = clamp_to(box.v1 + m, map.height() - 1);
  }
  const int extent = std::max(v.i1 - v.i0 + 1, v.j1 - v.j0 + 1);
  v.scale = std::clamp(o.target_pixels / extent, 1, o.max_scale);
  return v;
}

// Draws a map frame pose as pixels of the map area.
struct Projection {
  const OccupancyGrid& map;
  View v;
  figure::PlotArea area;
  [[nodiscard]] Point2 operator()(const Pose2& p) const {
    const Point2 c = to_cells(map, p);
    return {area.x + (c.x - v.i0) * v.scale, area.y + (v.j1 + 1 - c.y) * v.scale};
  }
};

void draw_cells(RgbImage& img, const Projection& at) {
  const View& v = at.v;
  for (int j = v.j0; j <= v.j1; ++j) {
    for (int i = v.i0; i <= v.i1; ++i) {
      const CellState s = at.map.at({i, j});
      const Rgb c = s == CellState::kFree       ? style::kFree
                    : s == CellState::kOccupied ? style::kOccupied
                                                : style::kUnknown;
      // image row 0 is the top (largest j)
      figure::fill_rect(img, at.area.x + (i - v.i0) * v.scale, at.area.y + (v.j1 - j) * v.scale,
                        v.scale, v.scale, c);
    }
  }
}

// The path's segments from pose k-1 to pose k for which keep(k) holds.
template <class Keep>
void polyline(RgbImage& img, const Projection& at, std::span<const logs::StampedPose> path,
              double width, Rgb c, Keep keep) {
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Point2 a = at(path[k - 1].pose);
    const Point2 b = at(path[k].pose);
    if (keep(k) && std::isfinite(a.x + a.y + b.x + b.y)) {
      figure::segment(img, a.x, a.y, b.x, b.y, width, c);
    }
  }
}

bool lost_at(const MapOverlay& o, std::size_t k) {
  return o.states.size() == o.estimate.size() && o.states[k] == LocalizationState::kLost;
}

void draw_paths(RgbImage& img, const Projection& at, const MapOverlay& o, const style::Strokes& s) {
  polyline(img, at, o.reference, s.reference, style::kReference, [](std::size_t) { return true; });
  // Joined from the settled pose on; the poses before it as dots.
  const auto joined = [&](std::size_t k) { return k > o.settled; };
  polyline(img, at, o.estimate, s.estimate, style::kEstimate, joined);
  polyline(img, at, o.estimate, s.lost, style::kLost,
           [&](std::size_t k) { return joined(k) && lost_at(o, k); });
  for (std::size_t k = 0; k < std::min(o.settled, o.estimate.size()); ++k) {
    const Point2 p = at(o.estimate[k].pose);
    if (std::isfinite(p.x + p.y)) {
      figure::disc(img, p.x, p.y, s.lost, lost_at(o, k) ? style::kLost : style::kEstimate);
    }
  }
}

void draw_markers(RgbImage& img, const Projection& at, const MapOverlay& o,
                  const style::Strokes& s) {
  if (o.start || !o.estimate.empty()) {
    // Not value_or(): its argument is evaluated even when the start is given, and a run with no
    // update has no front() to read.
    const Point2 start = at(o.start ? *o.start : o.estimate.front().pose);
    if (std::isfinite(start.x + start.y)) draw_start_marker(img, start.x, start.y, s.marker);
  }
  if (!o.estimate.empty()) {
    const Point2 end = at(o.estimate.back().pose);
    if (std::isfinite(end.x + end.y)) draw_end_marker(img, end.x, end.y, s.marker);
  }
  // The particles last: the end marker sits where they are.
  for (const Pose2& p : o.particles) {
    const Point2 px = at(p);
    if (std::isfinite(px.x + px.y)) figure::disc(img, px.x, px.y, s.particle, style::kParticle);
  }
}

// The axes' values: metres in the map frame, or from the grid's corner when the grid is
// rotated in the map frame (its rows are then not along the map's x axis).
std::pair<figure::Axis, figure::Axis> metre_axes(const OccupancyGrid& map, const View& v) {
  const double r = map.resolution();
  const bool aligned = map.origin().theta == 0.0;
  const double x0 = aligned ? map.origin().x : 0.0;
  const double y0 = aligned ? map.origin().y : 0.0;
  const std::string prefix = aligned ? "" : "grid ";
  return {figure::Axis{x0 + v.i0 * r, x0 + (v.i1 + 1) * r, prefix + "x (m)"},
          figure::Axis{y0 + v.j0 * r, y0 + (v.j1 + 1) * r, prefix + "y (m)"}};
}

}  // namespace

MapFigure render_map(const OccupancyGrid& map, const MapOverlay& overlay,
                     const MapRenderOptions& options) {
  const View v = choose_view(map, overlay, options);
  const int extent = std::max(v.i1 - v.i0 + 1, v.j1 - v.j0 + 1) * v.scale;
  const int text_scale = extent >= 400 ? 2 : 1;  // 10 x 14 px glyphs beside a map of that size
  const figure::PlotArea area{figure::left_margin(text_scale), kPad, (v.i1 - v.i0 + 1) * v.scale,
                              (v.j1 - v.j0 + 1) * v.scale};
  const LegendSpec legend = legend_for(overlay, map.resolution() / v.scale, v.scale, text_scale);
  MapFigure out{{}, area, v.scale};
  RgbImage& img = out.image;
  img.width = std::max(area.x + area.width + kPad, legend_min_width(legend));
  const int legend_top = area.y + area.height + figure::bottom_margin(text_scale) + kPad;
  img.height = legend_top + legend_height(legend, img.width);
  img.rgb.assign(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3U,
                 255);
  const Projection at{map, v, area};
  draw_cells(img, at);
  const style::Strokes strokes(v.scale);
  draw_paths(img, at, overlay, strokes);
  draw_markers(img, at, overlay, strokes);
  const auto [x_axis, y_axis] = metre_axes(map, v);
  figure::draw_axes(img, area, x_axis, y_axis, text_scale);
  draw_legend(img, legend, legend_top);
  return out;
}

void write_map_png(const std::filesystem::path& path, const OccupancyGrid& map,
                   const MapOverlay& overlay, const MapRenderOptions& options) {
  write_png(path, render_map(map, overlay, options).image);
}

}  // namespace mote::replay
