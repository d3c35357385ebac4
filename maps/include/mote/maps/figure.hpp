#pragma once
/// \file
/// Drawing into an RgbImage for mote's figures (map.png, calibration.png): pixels, discs,
/// thick segments, text in a built-in 5 x 7 bitmap font (no font library), and plot axes with
/// tick labels. Pixels outside the image are clipped, so callers may draw past the edges.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mote/maps/rgb_image.hpp"

namespace mote::figure {

using Rgb = std::array<std::uint8_t, 3>;

inline constexpr Rgb kBlack{0, 0, 0};
inline constexpr Rgb kWhite{255, 255, 255};

/// Sets one pixel; outside the image it does nothing.
void put(RgbImage& image, int x, int y, Rgb c);
/// Fills the w x h rectangle whose top-left pixel is (x, y).
void fill_rect(RgbImage& image, int x, int y, int w, int h, Rgb c);
/// The 1-pixel outline of the w x h rectangle whose top-left pixel is (x, y).
void outline_rect(RgbImage& image, int x, int y, int w, int h, Rgb c);
/// Fills the pixels whose centres lie within `radius` of (cx, cy), in pixel units.
void disc(RgbImage& image, double cx, double cy, double radius, Rgb c);
/// A segment `width` pixels wide (round caps) from (ax, ay) to (bx, by).
void segment(RgbImage& image, double ax, double ay, double bx, double by, double width, Rgb c);

/// Font cell: each glyph is 5 x 7 dots, advanced by 6 dots, times the scale in pixels.
inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = 6;

/// Width in pixels of `s` drawn at `scale` pixels per dot.
[[nodiscard]] int text_width(std::string_view s, int scale);
/// Height in pixels of a line of text at `scale`.
[[nodiscard]] constexpr int text_height(int scale) { return kGlyphHeight * scale; }
/// Draws `s` with its top-left corner at (x, y). The font has digits, lower-case letters
/// (upper case is drawn as lower case), space and . , - + * / ( ) : % = ^ ; other characters are
/// drawn as '?'.
void text(RgbImage& image, int x, int y, std::string_view s, int scale, Rgb c);
/// `s` drawn bottom to top (rotated 90 degrees anticlockwise), its bottom-left corner at
/// (x, y + text_width): for a vertical axis's label.
void text_up(RgbImage& image, int x, int y, std::string_view s, int scale, Rgb c);

/// Tick values on [lo, hi]: multiples of a step of 1, 2 or 5 times a power of ten, at most
/// `max_ticks` of them; {lo} when the range is empty.
[[nodiscard]] std::vector<double> ticks(double lo, double hi, int max_ticks);
/// `v` with as many decimals as the tick step needs ("-2", "0.5", "0.05").
[[nodiscard]] std::string tick_label(double v, double step);

/// A plot's pixel rectangle: (x, y) is its top-left pixel.
struct PlotArea {
  int x = 0, y = 0, width = 0, height = 0;
};

/// One axis of a plot: its value range, its title with the unit in brackets, and whether it is
/// logarithmic (base 10: ticks at the powers of ten).
struct Axis {
  double lo = 0.0, hi = 1.0;
  std::string title;
  bool log10 = false;
  /// Pixel offset of v along an axis `length` pixels long, 0 at lo (clamped to the axis).
  [[nodiscard]] double offset(double v, int length) const;
};

/// Room left of and below a plot that draw_axes needs for its tick labels and titles.
[[nodiscard]] int left_margin(int scale);
[[nodiscard]] int bottom_margin(int scale);

/// The plot's frame, ticks on its left and bottom edges with labels, and the axis titles
/// (x below, y rotated on the left). Text is drawn at `scale` pixels per font dot.
void draw_axes(RgbImage& image, const PlotArea& area, const Axis& x, const Axis& y, int scale);

}  // namespace mote::figure
