#pragma once
// map.png's legend (one sample and label per thing drawn, and a scale bar), laid out in rows
// below the map, and the start and end markers it shares with the map.
#include <string>
#include <vector>

#include "mote/maps/figure.hpp"
#include "mote/replay/map_image.hpp"

namespace mote::replay {

enum class LegendSample {
  kReference,
  kEstimate,
  kLost,
  kUnsettled,
  kParticles,
  kStart,
  kEnd,
  kScaleBar
};

struct LegendEntry {
  LegendSample sample;
  std::string label;
};

struct LegendSpec {
  std::vector<LegendEntry> entries;
  int cell_scale = 1;        ///< pixels per map cell, for the strokes' widths
  int text_scale = 1;        ///< pixels per font dot
  double scale_bar_m = 1.0;  ///< the scale bar's length
  int scale_bar_px = 1;
};

/// The entries for what the overlay draws; `metres_per_pixel` sizes the scale bar.
[[nodiscard]] LegendSpec legend_for(const MapOverlay& overlay, double metres_per_pixel,
                                    int cell_scale, int text_scale);
/// The narrowest image that fits the widest entry.
[[nodiscard]] int legend_min_width(const LegendSpec& spec);
/// The legend's height when the image is `width` pixels wide.
[[nodiscard]] int legend_height(const LegendSpec& spec, int width);
/// Draws the legend from row `top` down.
void draw_legend(RgbImage& image, const LegendSpec& spec, int top);

/// The estimate's start: a ring of radius r pixels.
void draw_start_marker(RgbImage& image, double x, double y, double r);
/// The estimate's end: a square outline of half side r pixels.
void draw_end_marker(RgbImage& image, double x, double y, double r);

}  // namespace mote::replay
