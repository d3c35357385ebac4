// Filling the likelihood table: grid cells get f(distance), the ring gets `outside`.
#include "mote/maps/likelihood_table.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/core/parallel.hpp"

namespace mote {

namespace {

int checked_border(int border, int grid_width, int grid_height) {
  if (border < 1 || border > 1'000'000) {
    throw ConfigError("likelihood table: border must be 1..1000000 cells, got " +
                      std::to_string(border));
  }
  // The float clamp bounds must stay exactly representable (2^24) and every index must fit
  // int32 (LikelihoodView::lookup gathers with 32-bit indices).
  const long long w = grid_width + 2LL * border;
  const long long h = grid_height + 2LL * border;
  if (w > (1 << 24) || h > (1 << 24) || w * h > 0x7FFFFFFFLL) {
    throw ConfigError("likelihood table: more than 2^24 cells a side or 2^31 cells in all");
  }
  return border;
}

TableTransform make_transform(double resolution, const Pose2& origin, int border, int width,
                              int height) {
  TableTransform t;
  t.cos_yaw = static_cast<float>(std::cos(origin.theta));
  t.sin_yaw = static_cast<float>(std::sin(origin.theta));
  t.origin_x = static_cast<float>(origin.x);
  t.origin_y = static_cast<float>(origin.y);
  t.inv_resolution = static_cast<float>(1.0 / resolution);
  t.border = static_cast<float>(border);
  t.max_col = static_cast<float>(width - 1);
  t.max_row = static_cast<float>(height - 1);
  return t;
}

}  // namespace

LikelihoodTable::LikelihoodTable(int width, int height, double resolution, const Pose2& origin,
                                 float outside, int border)
    : width_(width + 2 * checked_border(border, width, height)),
      height_(height + 2 * border),
      border_(border),
      stride_(static_cast<std::size_t>(width_)),
      outside_(outside),
      transform_(make_transform(resolution, origin, border, width_, height_)),
      values_(huge_pages::uninitialized<float>(stride_ * static_cast<std::size_t>(height_))) {
  // Only the ring holds `outside`; fill_rows writes every grid cell.
  const auto b = static_cast<std::size_t>(border);
  const auto rows = static_cast<std::size_t>(height_);
  float* v = values_.get();
  std::fill(v, v + b * stride_, outside);
  std::fill(v + (rows - b) * stride_, v + rows * stride_, outside);
  for (std::size_t j = b; j < rows - b; ++j) {
    std::fill(v + j * stride_, v + j * stride_ + b, outside);
    std::fill(v + (j + 1) * stride_ - b, v + (j + 1) * stride_, outside);
  }
}

template <typename Value>
void LikelihoodTable::fill_rows(const Value& value) {
  const auto b = static_cast<std::size_t>(border_);
  const std::size_t w = stride_ - 2 * b;
  par::for_each_chunk(static_cast<std::size_t>(height_) - 2 * b, /*grain=*/16,
                      [&](std::size_t j0, std::size_t j1) {
                        for (std::size_t j = j0; j < j1; ++j) {
                          float* row = values_.get() + (j + b) * stride_ + b;
                          for (std::size_t i = 0; i < w; ++i) row[i] = value(j * w + i);
                        }
                      });
}

LikelihoodTable::LikelihoodTable(const DistanceField& field, const std::function<float(float)>& f,
                                 float outside, int border)
    : LikelihoodTable(field.width(), field.height(), field.resolution(), field.origin(), outside,
                      border) {
  const float* distances = field.distances().data();
  fill_rows([&](std::size_t k) { return f(distances[k]); });
}

LikelihoodTable::LikelihoodTable(const SquaredDistances& field,
                                 const std::function<float(float)>& f, float outside, int border)
    : LikelihoodTable(field.width(), field.height(), field.resolution(), field.origin(), outside,
                      border) {
  // The value of every squared distance a cell can hold, then one load per cell.
  std::vector<float> by_squared(field.cap() + 1);
  for (std::uint32_t s = 0; s <= field.cap(); ++s) by_squared[s] = f(field.distance(s));
  const std::uint16_t* squared = field.data();
  fill_rows([&](std::size_t k) { return by_squared[squared[k]]; });
}

LikelihoodTable::LikelihoodTable(const OccupancyGrid& grid, ObstacleCells obstacles, float clamp,
                                 const std::function<float(float)>& f, float outside, int border)
    : LikelihoodTable(grid.width(), grid.height(), grid.resolution(), grid.origin(), outside,
                      border) {
  const int n =
      SquaredDistances::saturation(grid.resolution(), clamp, SquaredDistances::kMaxSaturation);
  if (n == 0) throw ConfigError("likelihood table: the clamp does not fit 255 cells");
  // DistanceField's value of each squared distance, then f of it, once per integer.
  std::vector<float> by_squared(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) + 1);
  for (std::size_t s = 0; s < by_squared.size(); ++s) {
    const auto d = static_cast<float>(std::sqrt(static_cast<double>(s)) * grid.resolution());
    by_squared[s] = f(std::min(d, clamp));
  }
  const auto b = static_cast<std::size_t>(border_);
  for_each_squared_row(
      grid, obstacles, n,
      [&](std::size_t j, std::size_t i0, std::size_t count, const std::uint16_t* s) {
        float* row = values_.get() + (j + b) * stride_ + b + i0;
        for (std::size_t i = 0; i < count; ++i) row[i] = by_squared[s[i]];
      });
}

}  // namespace mote
