// DIR/calibration.png, three titled panels side by side, each with axes in its units and a key:
//  1. the measured range error z - z* (-2 m .. +1 m, log-scale counts) as grey bars with the
//     fitted beam mixture's density over it (red), as Thrun et al. show it in figure 6.4;
//  2. heading residual of each odometry increment (-0.3 .. 0.3 rad) against the increment's
//     rotation (0 .. its 99th percentile), with the fitted 1- and 2-sigma bounds (blue) at the
//     median translation;
//  3. along-track residual (-0.3 .. 0.3 m) against the increment's translation (0 .. its 99th
//     percentile), bounds at the median rotation.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mote/calibrate/calibrate.hpp"
#include "mote/maps/figure.hpp"
#include "mote/maps/rgb_image.hpp"

namespace mote::calibrate {
namespace {

using figure::Rgb;

constexpr int kPanel = 300;  // px, each plot square
constexpr int kGap = 60;     // px, right of each panel: room for the key
constexpr int kText = 2;     // px per font dot
constexpr int kPad = 8;      // px
constexpr Rgb kBars{150, 150, 150};
constexpr Rgb kModel{220, 0, 0};
constexpr Rgb kPoints{0, 0, 0};
constexpr Rgb kBounds{0, 60, 220};
constexpr Rgb kZero{200, 200, 200};

// Height of the title and key rows above each plot.
constexpr int kHeader = kPad + 2 * (figure::text_height(kText) + kPad);

// One panel's plot: drawing in plot pixels, (0, 0) its top-left.
struct Panel {
  RgbImage& image;
  figure::PlotArea area;
  void dot(int x, int y, Rgb c) const {
    if (x >= 0 && y >= 0 && x < area.width && y < area.height) {
      figure::put(image, area.x + x, area.y + y, c);
    }
  }
};

struct KeyItem {
  Rgb colour;
  bool line;  // a line sample, else a dot
  std::string label;
};

// Maps a value in [lo, hi] to a pixel offset in [0, kPanel).
int pixel(double v, double lo, double hi) {
  return std::clamp(static_cast<int>((v - lo) / (hi - lo) * kPanel), 0, kPanel - 1);
}

// Title, key, axes and the grey zero line (a column zero_x or a row zero_y; -1 for none).
void decorate(const Panel& p, const std::string& title, const std::vector<KeyItem>& key,
              const figure::Axis& x, const figure::Axis& y, int zero_x, int zero_y) {
  const int title_y = p.area.y - kHeader + kPad;
  figure::text(p.image, p.area.x, title_y, title, kText, figure::kBlack);
  int kx = p.area.x;
  const int ky = title_y + figure::text_height(kText) + kPad;
  const int mid = ky + figure::text_height(kText) / 2;
  for (const KeyItem& k : key) {
    if (k.line) {
      figure::fill_rect(p.image, kx, mid - 1, 20, 3, k.colour);
    } else {
      figure::disc(p.image, kx + 10, mid, 3, k.colour);
    }
    figure::text(p.image, kx + 26, ky, k.label, kText, figure::kBlack);
    kx += 26 + figure::text_width(k.label, kText) + 16;
  }
  for (int k = 0; k < kPanel; ++k) {
    if (zero_x >= 0) p.dot(zero_x, k, kZero);
    if (zero_y >= 0) p.dot(k, zero_y, kZero);
  }
  figure::draw_axes(p.image, p.area, x, y, kText);
}

double mixture_density(const BeamSample& s, double e, double range_max, const BeamMixture& p) {
  const double z = s.expected + e;
  if (z < 0 || z >= range_max) return 0;
  double d = p.z_rand / range_max;
  if (s.expected < range_max) {
    d += p.z_hit * std::exp(-0.5 * e * e / (p.sigma_hit * p.sigma_hit)) /
         (std::sqrt(2 * std::numbers::pi) * p.sigma_hit);
  }
  if (z <= s.expected && s.expected > 0) {
    d += p.z_short * p.lambda_short * std::exp(-p.lambda_short * z) /
         -std::expm1(-p.lambda_short * s.expected);
  }
  return d;
}

constexpr double kErrLo = -2.0, kErrHi = 1.0;
constexpr int kBins = 150;

// Measured counts of z - z* per bin, and the fitted mixture's expected counts.
struct RangeHistogram {
  std::vector<double> count = std::vector<double>(kBins, 0.0);
  std::vector<double> model = std::vector<double>(kBins, 0.0);
};

RangeHistogram range_histogram(const CalibrationResult& r) {
  const double width = (kErrHi - kErrLo) / kBins;
  RangeHistogram h;
  const auto& beams = r.samples.beams;
  const BeamMixture& p = r.rounds.back().beam.params;
  const std::size_t stride = std::max<std::size_t>(1, beams.size() / 4000);  // model on a subset
  double model_n = 0;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const BeamSample& s = beams[i];
    const double e = s.measured - s.expected;
    if (s.measured < r.samples.range_max && e >= kErrLo && e < kErrHi) {
      h.count[static_cast<std::size_t>((e - kErrLo) / width)] += 1;
    }
    if (i % stride != 0) continue;
    model_n += 1;
    for (std::size_t b = 0; b < kBins; ++b) {
      h.model[b] += mixture_density(s, kErrLo + (static_cast<double>(b) + 0.5) * width,
                                    r.samples.range_max, p);
    }
  }
  const double scale = static_cast<double>(beams.size()) * width / std::max(model_n, 1.0);
  for (double& m : h.model) m *= scale;
  return h;
}

void range_panel(const Panel& p, const CalibrationResult& r) {
  const RangeHistogram h = range_histogram(r);
  const double top = std::max(10.0, static_cast<double>(r.samples.beams.size()) * 0.5);
  const figure::Axis counts{1.0, top, "beams per 2 cm", true};
  auto y_of = [&](double v) {
    return kPanel - 1 - static_cast<int>(counts.offset(std::max(v, 1.0), kPanel - 1));
  };
  int last = -1;
  for (std::size_t b = 0; b < kBins; ++b) {
    const int x = static_cast<int>(b) * 2;
    for (int yy = y_of(h.count[b]); yy < kPanel; ++yy) {
      p.dot(x, yy, kBars);
      p.dot(x + 1, yy, kBars);
    }
    const int y = y_of(h.model[b]);
    for (int yy = std::min(y, last < 0 ? y : last); yy <= std::max(y, last < 0 ? y : last); ++yy) {
      p.dot(x, yy, kModel);
      p.dot(x + 1, yy, kModel);
    }
    last = y;
  }
  decorate(p, "range error", {{kBars, true, "measured"}, {kModel, true, "fitted model"}},
           {kErrLo, kErrHi, "z - z* (m)"}, counts, pixel(0.0, kErrLo, kErrHi), -1);
}

// Scatter of residual (y) against a size (x), with the fitted sigma(x) drawn at +-1 and +-2.
template <class Residual, class Size, class Sigma>
void scatter_panel(const Panel& p, const CalibrationResult& r, Residual residual, Size size,
                   Sigma sigma, double xmax) {
  constexpr double ylim = 0.3;
  for (const MotionResidual& m : r.samples.motion) {
    p.dot(pixel(size(m), 0.0, xmax), kPanel - 1 - pixel(residual(m), -ylim, ylim), kPoints);
  }
  for (int px = 0; px < kPanel; ++px) {
    const double s = sigma((px + 0.5) / kPanel * xmax);
    for (const double k : {-2.0, -1.0, 1.0, 2.0}) {
      p.dot(px, kPanel - 1 - pixel(k * s, -ylim, ylim), kBounds);
    }
  }
}

// The q-quantile (0 <= q < 1) of v; 0 for none.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size()));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

Panel panel_at(RgbImage& image, int index) {
  const int column = figure::left_margin(kText) + kPanel + kGap;
  return {image, {kPad + index * column + figure::left_margin(kText), kHeader, kPanel, kPanel}};
}

void motion_panels(RgbImage& image, const CalibrationResult& r) {
  const OdometryAlphas& a = r.rounds.back().odometry.alphas_zero_mean;
  std::vector<double> trans, rot;
  for (const MotionResidual& m : r.samples.motion) {
    trans.push_back(m.trans);
    rot.push_back(std::abs(m.rot));
  }
  const double t_med = quantile(trans, 0.5), r_med = quantile(rot, 0.5);
  // x axes to the 99th percentile, so a few long increments do not squeeze the rest.
  const double t_max = std::max(0.05, quantile(trans, 0.99));
  const double r_max = std::max(0.05, quantile(rot, 0.99));
  const std::vector<KeyItem> key{{kPoints, false, "increments"}, {kBounds, true, "1, 2 sigma fit"}};
  const int zero = kPanel - 1 - pixel(0.0, -0.3, 0.3);
  // Heading: var = alpha1 (rot1^2 + rot2^2) + 2 alpha2 trans^2; drawn with rot1 = 0, rot2 = rot.
  const Panel heading = panel_at(image, 1);
  scatter_panel(
      heading, r, [](const MotionResidual& m) { return m.theta; },
      [](const MotionResidual& m) { return std::abs(m.rot); },
      [&](double x) { return std::sqrt(a.alpha1 * x * x + 2 * a.alpha2 * t_med * t_med); }, r_max);
  decorate(heading, "odometry heading error", key, {0.0, r_max, "rotation (rad)"},
           {-0.3, 0.3, "heading residual (rad)"}, -1, zero);
  const Panel along = panel_at(image, 2);
  scatter_panel(
      along, r, [](const MotionResidual& m) { return m.along; },
      [](const MotionResidual& m) { return m.trans; },
      [&](double x) { return std::sqrt(a.alpha3 * x * x + a.alpha4 * r_med * r_med); }, t_max);
  decorate(along, "odometry distance error", key, {0.0, t_max, "translation (m)"},
           {-0.3, 0.3, "along-track residual (m)"}, -1, zero);
}

}  // namespace

void write_calibration_png(const CalibrationResult& r, const std::filesystem::path& png) {
  RgbImage image;
  image.width = kPad + 3 * (figure::left_margin(kText) + kPanel + kGap);
  image.height = kHeader + kPanel + figure::bottom_margin(kText) + kPad;
  image.rgb.assign(static_cast<std::size_t>(image.width * image.height * 3), 255);
  range_panel(panel_at(image, 0), r);
  motion_panels(image, r);
  write_png(png, image);
}

}  // namespace mote::calibrate
