// The figures' drawing helpers: tick choice and labels, the bitmap font, axes.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "mote/maps/figure.hpp"

namespace mote::figure {
namespace {

RgbImage blank(int w, int h) {
  RgbImage img;
  img.width = w;
  img.height = h;
  img.rgb.assign(static_cast<std::size_t>(w * h * 3), 255);
  return img;
}

int dark_pixels(RgbImage& img, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) n += img.at(x, y)[0] < 128;
  }
  return n;
}

TEST(Figure, TicksAreRoundStepsInsideTheRange) {
  EXPECT_EQ(ticks(-2.0, 1.0, 7), (std::vector<double>{-2.0, -1.5, -1.0, -0.5, 0.0, 0.5, 1.0}));
  EXPECT_EQ(ticks(3.2, 47.0, 6), (std::vector<double>{10.0, 20.0, 30.0, 40.0}));
  const std::vector<double> small = ticks(0.0, 0.3, 7);
  EXPECT_DOUBLE_EQ(small[1], 0.05);
  EXPECT_EQ(small.size(), 7U);
  EXPECT_EQ(ticks(1.0, 1.0, 5), std::vector<double>{1.0});
}

TEST(Figure, TickLabelsHaveTheDecimalsTheStepNeeds) {
  EXPECT_EQ(tick_label(-2.0, 0.5), "-2.0");
  EXPECT_EQ(tick_label(20.0, 10.0), "20");
  EXPECT_EQ(tick_label(0.15, 0.05), "0.15");
  EXPECT_EQ(tick_label(-1e-12, 0.1), "0.0");
}

TEST(Figure, TextDrawsEachGlyphInItsCell) {
  RgbImage img = blank(60, 20);
  EXPECT_EQ(text_width("1.5 m", 2), (5 * kGlyphAdvance - 1) * 2);
  text(img, 0, 0, "1-", 2, kBlack);
  // '1' has a dot at column 2 of every row; '-' only row 3.
  EXPECT_EQ(img.at(2 * 2, 0)[0], 0);
  EXPECT_EQ(img.at(kGlyphAdvance * 2, 0)[0], 255);
  EXPECT_EQ(img.at(kGlyphAdvance * 2, 3 * 2)[0], 0);
  // Upper case is drawn as lower case; an unknown character as '?'.
  RgbImage upper = blank(60, 20), lower = blank(60, 20), odd = blank(60, 20), ask = blank(60, 20);
  text(upper, 0, 0, "M", 1, kBlack);
  text(lower, 0, 0, "m", 1, kBlack);
  text(odd, 0, 0, "@", 1, kBlack);
  text(ask, 0, 0, "?", 1, kBlack);
  EXPECT_EQ(upper.rgb, lower.rgb);
  EXPECT_EQ(odd.rgb, ask.rgb);
  EXPECT_GT(dark_pixels(lower, 0, 0, 5, 7), 10);
}

TEST(Figure, AxesLabelTheirTicksOutsideThePlot) {
  RgbImage img = blank(400, 300);
  const PlotArea area{left_margin(1), 10, 300, 200};
  draw_axes(img, area, Axis{0.0, 10.0, "x (m)"}, Axis{1.0, 1000.0, "count", true}, 1);
  EXPECT_EQ(img.at(area.x, area.y + 50)[0], 0);  // the frame
  EXPECT_EQ(
      dark_pixels(img, area.x + 1, area.y + 1, area.x + area.width - 1, area.y + area.height - 1),
      0);
  EXPECT_GT(dark_pixels(img, 0, area.y, area.x, area.y + area.height), 50);  // y labels, title
  EXPECT_GT(dark_pixels(img, area.x, area.y + area.height, area.x + area.width, 300), 50);
  EXPECT_DOUBLE_EQ((Axis{1.0, 1000.0, "", true}).offset(10.0, 300), 100.0);
}

}  // namespace
}  // namespace mote::figure
