// The figures' drawing primitives, tick choice and plot axes (figure.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mote/maps/figure.hpp"

namespace mote::figure {
namespace {

constexpr int kTick = 4;         // px, tick mark length
constexpr int kPad = 3;          // px, between a tick and its label
constexpr int kWidestLabel = 6;  // characters a y tick label is given room for

// Ticks of a log10 axis: the powers of ten inside [lo, hi].
std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> out;
  for (double p = std::ceil(std::log10(lo) - 1e-9); p <= std::log10(hi) + 1e-9; p += 1) {
    out.push_back(std::pow(10.0, p));
  }
  return out;
}

std::string log_label(double v) {
  const int power = static_cast<int>(std::lround(std::log10(v)));
  return power < 4 ? tick_label(v, 1.0) : "10^" + std::to_string(power);
}

void x_ticks(RgbImage& image, const PlotArea& a, const Axis& x, int scale) {
  // As many ticks as labels of five characters fit with a gap between them.
  const int room = text_width("-0.00", scale) + 4 * kPad;
  const int max_ticks = std::clamp(a.width / room, 2, 10);
  const std::vector<double> values = x.log10 ? log_ticks(x.lo, x.hi) : ticks(x.lo, x.hi, max_ticks);
  const double step = values.size() > 1 ? values[1] - values[0] : 1.0;
  const int bottom = a.y + a.height - 1;
  for (const double v : values) {
    const int px = a.x + static_cast<int>(std::lround(x.offset(v, a.width - 1)));
    fill_rect(image, px, bottom + 1, 1, kTick, kBlack);
    const std::string label = x.log10 ? log_label(v) : tick_label(v, step);
    text(image, px - text_width(label, scale) / 2, bottom + kTick + kPad, label, scale, kBlack);
  }
  const int title_y = bottom + kTick + 2 * kPad + text_height(scale) + kPad;
  text(image, a.x + (a.width - text_width(x.title, scale)) / 2, title_y, x.title, scale, kBlack);
}

void y_ticks(RgbImage& image, const PlotArea& a, const Axis& y, int scale) {
  const std::vector<double> values = y.log10 ? log_ticks(y.lo, y.hi) : ticks(y.lo, y.hi, 6);
  const double step = values.size() > 1 ? values[1] - values[0] : 1.0;
  const int bottom = a.y + a.height - 1;
  for (const double v : values) {
    const int py = bottom - static_cast<int>(std::lround(y.offset(v, a.height - 1)));
    fill_rect(image, a.x - kTick, py, kTick, 1, kBlack);
    const std::string label = y.log10 ? log_label(v) : tick_label(v, step);
    const int lx = a.x - kTick - kPad - text_width(label, scale);
    text(image, lx, py - text_height(scale) / 2, label, scale, kBlack);
  }
  const int title_x = a.x - left_margin(scale);
  text_up(image, title_x, a.y + (a.height - text_width(y.title, scale)) / 2, y.title, scale,
          kBlack);
}

}  // namespace

void put(RgbImage& image, int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  std::copy(c.begin(), c.end(), image.at(x, y));
}

void fill_rect(RgbImage& image, int x, int y, int w, int h, Rgb c) {
  for (int dy = 0; dy < h; ++dy) {
    for (int dx = 0; dx < w; ++dx) put(image, x + dx, y + dy, c);
  }
}

void outline_rect(RgbImage& image, int x, int y, int w, int h, Rgb c) {
  fill_rect(image, x, y, w, 1, c);
  fill_rect(image, x, y + h - 1, w, 1, c);
  fill_rect(image, x, y, 1, h, c);
  fill_rect(image, x + w - 1, y, 1, h, c);
}

void disc(RgbImage& image, double cx, double cy, double radius, Rgb c) {
  const int x0 = static_cast<int>(std::floor(cx - radius));
  const int y0 = static_cast<int>(std::floor(cy - radius));
  const int n = static_cast<int>(std::ceil(2 * radius)) + 1;
  // Squares, not hypot: a global start's map draws 500k particles (0.2 s of hypot calls).
  const double r2 = radius * radius;
  for (int y = y0; y <= y0 + n; ++y) {
    const double dy = y + 0.5 - cy;
    for (int x = x0; x <= x0 + n; ++x) {
      const double dx = x + 0.5 - cx;
      if (dx * dx + dy * dy <= r2) put(image, x, y, c);
    }
  }
}

void segment(RgbImage& image, double ax, double ay, double bx, double by, double width, Rgb c) {
  const double length = std::hypot(bx - ax, by - ay);
  // Discs every half pixel; a far-off end (an estimate's jump) is clipped by put().
  const double bound = 4.0 * (image.width + image.height);
  const int steps = static_cast<int>(std::min(bound, 2.0 * length)) + 1;
  const double radius = std::max(0.5, width / 2);
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    disc(image, ax + t * (bx - ax), ay + t * (by - ay), radius, c);
  }
}

std::vector<double> ticks(double lo, double hi, int max_ticks) {
  if (!(hi > lo) || max_ticks < 2) return {lo};
  const double raw = (hi - lo) / (max_ticks - 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * magnitude;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * magnitude >= raw) {
      step = m * magnitude;
      break;
    }
  }
  std::vector<double> out;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) {
    out.push_back(std::abs(v) < step * 1e-6 ? 0.0 : v);
  }
  return out;
}

std::string tick_label(double v, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buffer;
}

double Axis::offset(double v, int length) const {
  const double t =
      log10 ? (std::log10(std::max(v, lo)) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
            : (v - lo) / (hi - lo);
  return std::clamp(t, 0.0, 1.0) * length;
}

int left_margin(int scale) {
  return text_height(scale) + 2 * kPad + text_width(std::string(kWidestLabel, '0'), scale) + kPad +
         kTick;
}

int bottom_margin(int scale) { return kTick + 3 * kPad + 2 * text_height(scale) + kPad; }

void draw_axes(RgbImage& image, const PlotArea& area, const Axis& x, const Axis& y, int scale) {
  outline_rect(image, area.x, area.y, area.width, area.height, kBlack);
  x_ticks(image, area, x, scale);
  y_ticks(image, area, y, scale);
}

}  // namespace mote::figure
