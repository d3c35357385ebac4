#pragma once
// Helpers shared by the engine tests: sample statistics with their standard errors, and a
// FreeSpace made of unit cells so recovery tests need no map.

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "mote/core/free_space.hpp"

namespace mote::test {

/// Mean and (unbiased) variance of a sample.
struct SampleStats {
  double mean = 0.0;
  double variance = 0.0;
  std::size_t n = 0;

  /// 5 standard errors of the mean (sd / sqrt(n)): a correct estimator fails this with
  /// probability about 6e-7.
  [[nodiscard]] double mean_tolerance() const {
    return 5.0 * std::sqrt(variance / static_cast<double>(n));
  }
  /// 5 standard errors of the sample variance of a Gaussian, var * sqrt(2 / (n - 1)).
  [[nodiscard]] double variance_tolerance(double true_variance) const {
    return 5.0 * true_variance * std::sqrt(2.0 / static_cast<double>(n - 1));
  }
};

template <class F>
SampleStats sample_stats(std::size_t n, const F& value) {
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += value(i);
  const double mean = sum / static_cast<double>(n);
  double sq = 0.0;
  for (std::size_t i = 0; i < n; ++i) sq += (value(i) - mean) * (value(i) - mean);
  return {mean, sq / static_cast<double>(n - 1), n};
}

/// Free space made of 1 m x 1 m cells whose lower-left corners are given.
class CellFreeSpace : public FreeSpace {
 public:
  explicit CellFreeSpace(std::vector<Point2> corners) : corners_(std::move(corners)) {}
  [[nodiscard]] std::size_t free_cell_count() const noexcept override { return corners_.size(); }
  [[nodiscard]] Point2 free_point(std::size_t k, double u, double v) const noexcept override {
    return {corners_[k].x + u, corners_[k].y + v};
  }
  [[nodiscard]] Bounds2 bounds() const noexcept override { return {-10.0, -10.0, 10.0, 10.0}; }
  /// True when (x, y) lies in one of the cells.
  [[nodiscard]] bool contains(double x, double y) const {
    for (const Point2& c : corners_) {
      if (x >= c.x && x <= c.x + 1.0 && y >= c.y && y <= c.y + 1.0) return true;
    }
    return false;
  }

 private:
  std::vector<Point2> corners_;
};

}  // namespace mote::test
