// map.png: grid cells to pixels, polylines and particle dots (written by maps' write_png).
#include "mote/replay/map_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace mote::replay {
namespace {

using Color = std::array<std::uint8_t, 3>;
constexpr Color kFree{255, 255, 255};
constexpr Color kOccupied{0, 0, 0};
constexpr Color kUnknown{160, 160, 160};
constexpr Color kReference{0, 170, 0};
constexpr Color kEstimate{220, 20, 20};
constexpr Color kParticle{40, 90, 255};

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

void fill(RgbImage& img, int x, int y, Color c) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  std::copy(c.begin(), c.end(), img.at(x, y));
}

void draw_cells(RgbImage& img, const OccupancyGrid& map, const View& v) {
  for (int j = v.j0; j <= v.j1; ++j) {
    for (int i = v.i0; i <= v.i1; ++i) {
      const CellState s = map.at({i, j});
      const Color c = s == CellState::kFree       ? kFree
                      : s == CellState::kOccupied ? kOccupied
                                                  : kUnknown;
      const int px = (i - v.i0) * v.scale;
      const int py = (v.j1 - j) * v.scale;  // image row 0 is the top (largest j)
      for (int dy = 0; dy < v.scale; ++dy) {
        for (int dx = 0; dx < v.scale; ++dx) fill(img, px + dx, py + dy, c);
      }
    }
  }
}

// Pixel coordinates (fractional) of a map frame pose.
Point2 to_pixel(const OccupancyGrid& map, const View& v, const Pose2& p) {
  const Point2 c = to_cells(map, p);
  return {(c.x - v.i0) * v.scale, (v.j1 + 1 - c.y) * v.scale};
}

void dot(RgbImage& img, Point2 p, int size, Color c) {
  const int x0 = static_cast<int>(std::floor(p.x)) - size / 2;
  const int y0 = static_cast<int>(std::floor(p.y)) - size / 2;
  for (int dy = 0; dy < size; ++dy) {
    for (int dx = 0; dx < size; ++dx) fill(img, x0 + dx, y0 + dy, c);
  }
}

// A segment as dots every half pixel; far-off segments (estimate jumps) are clipped by fill().
void segment(RgbImage& img, Point2 a, Point2 b, int width, Color c) {
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int steps = static_cast<int>(std::min(4.0 * (img.width + img.height), 2.0 * length)) + 1;
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    dot(img, {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}, width, c);
  }
}

void polyline(RgbImage& img, const OccupancyGrid& map, const View& v,
              std::span<const logs::StampedPose> path, Color c) {
  const int width = std::max(2, v.scale / 2);
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Point2 a = to_pixel(map, v, path[k - 1].pose);
    const Point2 b = to_pixel(map, v, path[k].pose);
    if (std::isfinite(a.x + a.y + b.x + b.y)) segment(img, a, b, width, c);
  }
}

}  // namespace

RgbImage render_map(const OccupancyGrid& map, const MapOverlay& overlay,
                    const MapRenderOptions& options) {
  const View v = choose_view(map, overlay, options);
  RgbImage img;
  img.width = (v.i1 - v.i0 + 1) * v.scale;
  img.height = (v.j1 - v.j0 + 1) * v.scale;
  img.rgb.assign(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3U,
                 0);
  draw_cells(img, map, v);
  const int dot_size = std::max(1, v.scale / 2);
  for (const Pose2& p : overlay.particles) {
    const Point2 px = to_pixel(map, v, p);
    if (std::isfinite(px.x + px.y)) dot(img, px, dot_size, kParticle);
  }
  polyline(img, map, v, overlay.reference, kReference);
  polyline(img, map, v, overlay.estimate, kEstimate);
  return img;
}

void write_map_png(const std::filesystem::path& path, const OccupancyGrid& map,
                   const MapOverlay& overlay, const MapRenderOptions& options) {
  write_png(path, render_map(map, overlay, options));
}

}  // namespace mote::replay
