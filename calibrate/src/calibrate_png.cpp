// DIR/calibration.png, three panels side by side (no text; docs/calibration.md explains the axes):
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

#include "mote/calibrate/calibrate.hpp"
#include "mote/maps/rgb_image.hpp"

namespace mote::calibrate {
namespace {

constexpr int kPanel = 300;  // px, each panel square
constexpr int kGap = 10;

struct Canvas {
  RgbImage image;
  void dot(int x, int y, std::array<std::uint8_t, 3> c) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    std::uint8_t* p = image.at(x, y);
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
  }
};

// Maps a value in [lo, hi] to a pixel offset in [0, kPanel).
int pixel(double v, double lo, double hi) {
  return std::clamp(static_cast<int>((v - lo) / (hi - lo) * kPanel), 0, kPanel - 1);
}

// The panel's border, and a grey line at zero: vertical at column zero_x, or horizontal at
// row zero_y (-1 for none).
void frame(Canvas& c, int x0, int zero_x, int zero_y) {
  for (int k = 0; k < kPanel; ++k) {
    c.dot(x0 + k, 0, {0, 0, 0});
    c.dot(x0 + k, kPanel - 1, {0, 0, 0});
    c.dot(x0, k, {0, 0, 0});
    c.dot(x0 + kPanel - 1, k, {0, 0, 0});
    if (zero_x >= 0) c.dot(x0 + zero_x, k, {200, 200, 200});
    if (zero_y >= 0) c.dot(x0 + k, zero_y, {200, 200, 200});
  }
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

void range_panel(Canvas& c, const CalibrationResult& r) {
  constexpr double lo = -2.0, hi = 1.0;
  constexpr int bins = 150;
  const double width = (hi - lo) / bins;
  std::vector<double> count(bins, 0.0), model(bins, 0.0);
  const auto& beams = r.samples.beams;
  const BeamMixture& p = r.rounds.back().beam.params;
  const std::size_t stride = std::max<std::size_t>(1, beams.size() / 4000);  // model on a subset
  double model_n = 0;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const BeamSample& s = beams[i];
    const double e = s.measured - s.expected;
    if (s.measured < r.samples.range_max && e >= lo && e < hi) {
      count[static_cast<std::size_t>((e - lo) / width)] += 1;
    }
    if (i % stride != 0) continue;
    model_n += 1;
    for (int b = 0; b < bins; ++b) {
      model[static_cast<std::size_t>(b)] +=
          mixture_density(s, lo + (b + 0.5) * width, r.samples.range_max, p);
    }
  }
  const auto n = static_cast<double>(beams.size());
  const double top = std::log10(std::max(1.0, n * 0.5));  // log-count scale: 1 .. n / 2
  auto y_of = [&](double v) { return kPanel - 1 - pixel(std::log10(std::max(v, 1.0)), 0.0, top); };
  for (int b = 0; b < bins; ++b) {
    const int y = y_of(count[static_cast<std::size_t>(b)]);
    for (int x = b * 2; x < b * 2 + 2; ++x) {
      for (int yy = y; yy < kPanel; ++yy) c.dot(x, yy, {150, 150, 150});
    }
  }
  int last = -1;
  for (int b = 0; b < bins; ++b) {
    const double expected_count =
        model[static_cast<std::size_t>(b)] / std::max(model_n, 1.0) * n * width;
    const int y = y_of(expected_count);
    for (int yy = std::min(y, last < 0 ? y : last); yy <= std::max(y, last < 0 ? y : last); ++yy) {
      c.dot(b * 2, yy, {220, 0, 0});
      c.dot(b * 2 + 1, yy, {220, 0, 0});
    }
    last = y;
  }
  frame(c, 0, pixel(0.0, lo, hi), -1);
}

// Scatter of residual (y) against a size (x), with the fitted sigma(x) drawn at +-1 and +-2.
template <class Residual, class Size, class Sigma>
void scatter_panel(Canvas& c, int x0, const CalibrationResult& r, Residual residual, Size size,
                   Sigma sigma, double xmax) {
  constexpr double ylim = 0.3;
  for (const MotionResidual& m : r.samples.motion) {
    c.dot(x0 + pixel(size(m), 0.0, xmax), kPanel - 1 - pixel(residual(m), -ylim, ylim), {0, 0, 0});
  }
  for (int px = 0; px < kPanel; ++px) {
    const double s = sigma((px + 0.5) / kPanel * xmax);
    for (const double k : {-2.0, -1.0, 1.0, 2.0}) {
      c.dot(x0 + px, kPanel - 1 - pixel(k * s, -ylim, ylim), {0, 60, 220});
    }
  }
  frame(c, x0, -1, kPanel - 1 - pixel(0.0, -ylim, ylim));
}

// The q-quantile (0 <= q < 1) of v; 0 for none.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size()));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

void write_calibration_png(const CalibrationResult& r, const std::filesystem::path& png) {
  Canvas c;
  c.image.width = 3 * kPanel + 2 * kGap;
  c.image.height = kPanel;
  c.image.rgb.assign(static_cast<std::size_t>(c.image.width * c.image.height * 3), 255);
  range_panel(c, r);
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
  // Heading: var = alpha1 (rot1^2 + rot2^2) + 2 alpha2 trans^2; drawn with rot1 = 0, rot2 = rot.
  scatter_panel(
      c, kPanel + kGap, r, [](const MotionResidual& m) { return m.theta; },
      [](const MotionResidual& m) { return std::abs(m.rot); },
      [&](double x) { return std::sqrt(a.alpha1 * x * x + 2 * a.alpha2 * t_med * t_med); }, r_max);
  scatter_panel(
      c, 2 * (kPanel + kGap), r, [](const MotionResidual& m) { return m.along; },
      [](const MotionResidual& m) { return m.trans; },
      [&](double x) { return std::sqrt(a.alpha3 * x * x + a.alpha4 * r_med * r_med); }, t_max);
  write_png(png, c.image);
}

}  // namespace mote::calibrate
