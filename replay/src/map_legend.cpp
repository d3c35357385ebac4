// map.png's legend: samples drawn with the map's own strokes, flowed into rows.
#include "map_legend.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "map_style.hpp"

namespace mote::replay {
namespace {

namespace style = map_style;

constexpr int kMargin = 12;    // px, left of the first entry and between rows
constexpr int kSample = 36;    // px, width of a line sample
constexpr int kSpacing = 22;   // px, between entries
constexpr int kLabelGap = 12;  // px, between a sample and its label

int sample_width(const LegendSpec& spec, const LegendEntry& e) {
  return e.sample == LegendSample::kScaleBar ? spec.scale_bar_px : kSample;
}

int entry_width(const LegendSpec& spec, const LegendEntry& e) {
  return sample_width(spec, e) + kLabelGap + figure::text_width(e.label, spec.text_scale);
}

int row_height(const LegendSpec& spec) {
  const style::Strokes s(spec.cell_scale);
  return std::max(figure::text_height(spec.text_scale), static_cast<int>(2 * s.marker + 2)) +
         kMargin / 2;
}

// Calls place(entry, x, row) for each entry flowed into rows of `width` pixels.
template <class Place>
int flow(const LegendSpec& spec, int width, Place place) {
  int x = kMargin, row = 0;
  for (const LegendEntry& e : spec.entries) {
    const int w = entry_width(spec, e);
    if (x > kMargin && x + w > width - kMargin) {
      x = kMargin;
      ++row;
    }
    place(e, x, row);
    x += w + kSpacing;
  }
  return spec.entries.empty() ? 0 : row + 1;
}

void draw_scale_bar(RgbImage& img, int x, int cy, int length) {
  figure::fill_rect(img, x, cy - 1, length, 3, figure::kBlack);
  figure::fill_rect(img, x, cy - 6, 2, 12, figure::kBlack);
  figure::fill_rect(img, x + length - 2, cy - 6, 2, 12, figure::kBlack);
}

void draw_sample(RgbImage& img, const LegendSpec& spec, LegendSample what, int x, int cy) {
  const style::Strokes s(spec.cell_scale);
  const double mid = x + kSample / 2.0;
  switch (what) {
    case LegendSample::kReference:
      figure::segment(img, x, cy, x + kSample, cy, s.reference, style::kReference);
      break;
    case LegendSample::kEstimate:
      figure::segment(img, x, cy, x + kSample, cy, s.estimate, style::kEstimate);
      break;
    case LegendSample::kLost:
      figure::segment(img, x, cy, x + kSample, cy, s.lost, style::kLost);
      break;
    case LegendSample::kUnsettled:
      for (const double dx : {-12.0, 0.0, 12.0})
        figure::disc(img, mid + dx, cy, s.lost, style::kEstimate);
      break;
    case LegendSample::kParticles:
      for (const double dx : {-10.0, 0.0, 10.0}) {
        figure::disc(img, mid + dx, cy + (dx == 0.0 ? -3 : 3), s.particle, style::kParticle);
      }
      break;
    case LegendSample::kStart:
      draw_start_marker(img, mid, cy, s.marker);
      break;
    case LegendSample::kEnd:
      draw_end_marker(img, mid, cy, s.marker);
      break;
    case LegendSample::kScaleBar:
      draw_scale_bar(img, x, cy, spec.scale_bar_px);
      break;
  }
}

}  // namespace

LegendSpec legend_for(const MapOverlay& overlay, double metres_per_pixel, int cell_scale,
                      int text_scale) {
  LegendSpec spec;
  spec.cell_scale = cell_scale;
  spec.text_scale = text_scale;
  const bool lost = std::ranges::count(overlay.states, LocalizationState::kLost) > 0;
  if (!overlay.reference.empty()) spec.entries.push_back({LegendSample::kReference, "reference"});
  if (!overlay.estimate.empty()) {
    spec.entries.push_back({LegendSample::kEstimate,
                            lost || overlay.states.empty() ? "estimate" : "estimate (never lost)"});
  }
  if (lost) spec.entries.push_back({LegendSample::kLost, "estimate while lost"});
  if (overlay.settled > 0 && !overlay.estimate.empty()) {
    spec.entries.push_back({LegendSample::kUnsettled, "estimate before it settled"});
  }
  if (!overlay.particles.empty()) {
    spec.entries.push_back({LegendSample::kParticles, "final particles"});
  }
  if (overlay.start || !overlay.estimate.empty()) {
    spec.entries.push_back({LegendSample::kStart, overlay.start_label});
  }
  if (!overlay.estimate.empty()) spec.entries.push_back({LegendSample::kEnd, "end"});
  // A round length of 60 to 150 pixels.
  const std::vector<double> t = figure::ticks(0.0, 120.0 * metres_per_pixel, 3);
  spec.scale_bar_m = t.size() > 1 ? t[1] : 120.0 * metres_per_pixel;
  spec.scale_bar_px = static_cast<int>(std::lround(spec.scale_bar_m / metres_per_pixel));
  spec.entries.push_back(
      {LegendSample::kScaleBar, figure::tick_label(spec.scale_bar_m, spec.scale_bar_m) + " m"});
  return spec;
}

int legend_min_width(const LegendSpec& spec) {
  int widest = 0;
  for (const LegendEntry& e : spec.entries) widest = std::max(widest, entry_width(spec, e));
  return widest + 2 * kMargin;
}

int legend_height(const LegendSpec& spec, int width) {
  return flow(spec, width, [](const LegendEntry&, int, int) {}) * row_height(spec) + kMargin;
}

void draw_legend(RgbImage& image, const LegendSpec& spec, int top) {
  const int h = row_height(spec);
  flow(spec, image.width, [&](const LegendEntry& e, int x, int row) {
    const int cy = top + row * h + h / 2;
    draw_sample(image, spec, e.sample, x, cy);
    const int label_x = x + sample_width(spec, e) + kLabelGap;
    figure::text(image, label_x, cy - figure::text_height(spec.text_scale) / 2, e.label,
                 spec.text_scale, figure::kBlack);
  });
}

void draw_start_marker(RgbImage& image, double x, double y, double r) {
  constexpr int kSteps = 48;
  for (int k = 0; k < kSteps; ++k) {
    const double a0 = 2 * std::numbers::pi * k / kSteps;
    const double a1 = 2 * std::numbers::pi * (k + 1) / kSteps;
    figure::segment(image, x + r * std::cos(a0), y + r * std::sin(a0), x + r * std::cos(a1),
                    y + r * std::sin(a1), 3.0, style::kStart);
  }
}

void draw_end_marker(RgbImage& image, double x, double y, double r) {
  const int x0 = static_cast<int>(std::lround(x - r));
  const int y0 = static_cast<int>(std::lround(y - r));
  const int side = static_cast<int>(std::lround(2 * r)) + 1;
  for (int k = 0; k < 3; ++k) {
    figure::outline_rect(image, x0 + k, y0 + k, side - 2 * k, side - 2 * k, style::kEnd);
  }
}

}  // namespace mote::replay
