// Grid localization, Thrun et al., Probabilistic Robotics, section 8.2 and table 8.1.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/sensor_model.hpp"
#include "mote/filters/histogram_filter.hpp"

namespace mote {
namespace {

void check_config(const GridLocalizationConfig& c) {
  if (c.cell_stride < 1 || c.headings < 1 || c.subsamples < 1 || !(c.kernel_sigmas > 0.0)) {
    throw ConfigError(
        "GridLocalization: cell_stride, headings and subsamples must be >= 1 and kernel_sigmas "
        "> 0");
  }
}

// Rows of the belief (one heading, one j) per task in the parallel passes.
constexpr std::size_t kRowGrain = 16;

}  // namespace

GridLocalization::GridLocalization(const OccupancyGrid& grid, const GridLocalizationConfig& config)
    : origin_(grid.origin()),
      cos_yaw_(std::cos(grid.origin().theta)),
      sin_yaw_(std::sin(grid.origin().theta)),
      config_((check_config(config), config)),
      nx_((grid.width() + config.cell_stride - 1) / config.cell_stride),
      ny_((grid.height() + config.cell_stride - 1) / config.cell_stride),
      nt_(config.headings),
      cell_(grid.resolution() * config.cell_stride),
      sensor_(grid, config.sensor) {
  free_.resize(plane());
  for (std::size_t k = 0; k < plane(); ++k) {
    const Pose2 p = state_pose(k);
    free_[k] = grid.at_or(grid.world_to_cell({p.x, p.y}), CellState::kOccupied) == CellState::kFree;
  }
  belief_.resize(plane() * static_cast<std::size_t>(nt_));
  next_.resize(belief_.size());
  centres_.resize(belief_.size());
  const ParticleView v = centres_.view();
  for (std::size_t k = 0; k < belief_.size(); ++k) v.set_pose(k, state_pose(k));
  set_uniform();
}

double GridLocalization::heading_of(int t) const noexcept {
  return -std::numbers::pi + (t + 0.5) * 2.0 * std::numbers::pi / nt_;
}

Pose2 GridLocalization::state_pose(std::size_t k) const noexcept {
  const auto i = static_cast<double>(k % static_cast<std::size_t>(nx_));
  const auto j =
      static_cast<double>((k / static_cast<std::size_t>(nx_)) % static_cast<std::size_t>(ny_));
  const int t = static_cast<int>(k / plane());
  const double gx = (i + 0.5) * cell_;
  const double gy = (j + 0.5) * cell_;
  return {origin_.x + cos_yaw_ * gx - sin_yaw_ * gy, origin_.y + sin_yaw_ * gx + cos_yaw_ * gy,
          heading_of(t)};
}

std::size_t GridLocalization::state_of(const Pose2& p) const noexcept {
  const double dx = p.x - origin_.x;
  const double dy = p.y - origin_.y;
  const double i = std::floor((cos_yaw_ * dx + sin_yaw_ * dy) / cell_);
  const double j = std::floor((cos_yaw_ * dy - sin_yaw_ * dx) / cell_);
  if (!(i >= 0 && j >= 0 && i < nx_ && j < ny_)) return npos;
  const double turns = (wrap_angle(p.theta) + std::numbers::pi) / (2.0 * std::numbers::pi);
  const int t = std::min(nt_ - 1, static_cast<int>(std::floor(turns * nt_)));
  return (static_cast<std::size_t>(t) * static_cast<std::size_t>(ny_) +
          static_cast<std::size_t>(j)) *
             static_cast<std::size_t>(nx_) +
         static_cast<std::size_t>(i);
}

void GridLocalization::set_uniform() {
  for (std::size_t k = 0; k < belief_.size(); ++k) belief_[k] = is_free(k) ? 1.0 : 0.0;
  normalize_belief("GridLocalization::set_uniform (the grid has no free cell)");
}

void GridLocalization::set_belief(std::vector<double> belief) {
  if (belief.size() != belief_.size()) {
    throw ConfigError("GridLocalization::set_belief: " + std::to_string(belief.size()) +
                      " values, expected " + std::to_string(belief_.size()));
  }
  if (std::any_of(belief.begin(), belief.end(),
                  [](double b) { return !(b >= 0.0) || !std::isfinite(b); })) {
    throw ConfigError("GridLocalization::set_belief: values must be finite and non-negative");
  }
  belief_ = std::move(belief);
  normalize_belief("GridLocalization::set_belief (the belief sums to 0)");
}

void GridLocalization::normalize_belief(const char* where) {
  const double total = par::reduce(
      belief_.size(), 4096, 0.0,
      /*partial=*/
      [&](std::size_t b, std::size_t e) {
        double s = 0.0;
        for (std::size_t k = b; k < e; ++k) s += belief_[k];
        return s;
      },
      /*join=*/[](double a, double b) { return a + b; });
  if (!(total > 0.0) || !std::isfinite(total)) throw ConfigError(std::string(where));
  par::for_each_chunk(belief_.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) belief_[k] /= total;
  });
}

void GridLocalization::predict(const MotionKernel& kernel) {
  if (kernel.by_to.size() != static_cast<std::size_t>(nt_)) {
    throw ConfigError("GridLocalization::predict: the kernel has " +
                      std::to_string(kernel.by_to.size()) + " headings, expected " +
                      std::to_string(nt_));
  }
  const auto nx = static_cast<std::ptrdiff_t>(nx_);
  // Gather form of the convolution: every output row sums its sources in the kernel's fixed
  // order, so the result does not depend on the thread count; the inner loop is contiguous.
  par::for_each_chunk(
      static_cast<std::size_t>(nt_ * ny_), kRowGrain, [&](std::size_t b, std::size_t e) {
        for (std::size_t row = b; row < e; ++row) {
          const int t = static_cast<int>(row / static_cast<std::size_t>(ny_));
          const int j = static_cast<int>(row % static_cast<std::size_t>(ny_));
          double* out = next_.data() + row * static_cast<std::size_t>(nx_);
          std::fill(out, out + nx_, 0.0);
          for (const MotionKernelEntry& k : kernel.by_to[static_cast<std::size_t>(t)]) {
            const int js = j - k.dj;
            if (js < 0 || js >= ny_) continue;
            const double* in =
                belief_.data() + (static_cast<std::size_t>(k.from) * static_cast<std::size_t>(ny_) +
                                  static_cast<std::size_t>(js)) *
                                     static_cast<std::size_t>(nx_);
            const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(0, k.di);
            const std::ptrdiff_t hi = std::min<std::ptrdiff_t>(nx, nx + k.di);
            for (std::ptrdiff_t i = lo; i < hi; ++i) out[i] += k.p * in[i - k.di];
          }
        }
      });
  belief_.swap(next_);
  normalize_belief("GridLocalization::predict: every state moved off the grid");
}

std::vector<float> GridLocalization::measurement_log_likelihood(const BeamSet& beams) {
  sensor_.prepare(beams);
  const ParticleView v = centres_.view();
  std::fill(v.logw, v.logw + v.size(), 0.0F);
  weigh_scan(sensor_, beams, v);
  std::vector<float> out(v.logw, v.logw + v.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (!is_free(k)) out[k] = -std::numeric_limits<float>::infinity();
  }
  return out;
}

double GridLocalization::correct(const std::vector<float>& loglik) {
  if (loglik.size() != belief_.size()) {
    throw ConfigError("GridLocalization::correct: " + std::to_string(loglik.size()) +
                      " log-likelihoods, expected " + std::to_string(belief_.size()));
  }
  // Shift by the largest log-likelihood among states with belief before exponentiating.
  float top = -std::numeric_limits<float>::infinity();
  for (std::size_t k = 0; k < loglik.size(); ++k) {
    if (belief_[k] > 0.0) top = std::max(top, loglik[k]);
  }
  if (!std::isfinite(top)) {
    throw ConfigError("GridLocalization::correct: no state with belief explains the scan");
  }
  double total = 0.0;
  for (std::size_t k = 0; k < loglik.size(); ++k) {
    belief_[k] *= std::exp(static_cast<double>(loglik[k]) - top);
    total += belief_[k];
  }
  normalize_belief("GridLocalization::correct: no state with belief explains the scan");
  return static_cast<double>(top) + std::log(total);
}

std::vector<double> GridLocalization::marginal_xy() const {
  std::vector<double> m(plane(), 0.0);
  for (std::size_t k = 0; k < belief_.size(); ++k) m[k % plane()] += belief_[k];
  return m;
}

}  // namespace mote
