#include "mote/maps/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"

namespace mote {

namespace {
void check_shape(int width, int height, double resolution, std::size_t cell_count) {
  if (width <= 0 || height <= 0) {
    throw ConfigError("occupancy grid: width and height must be positive, got " +
                      std::to_string(width) + " x " + std::to_string(height));
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw ConfigError("occupancy grid: resolution must be a positive number of metres, got " +
                      std::to_string(resolution));
  }
  const auto expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (cell_count != expected) {
    throw ConfigError("occupancy grid: expected " + std::to_string(expected) + " cells, got " +
                      std::to_string(cell_count));
  }
  if (expected > std::size_t{0xFFFFFFFFU}) {
    throw ConfigError("occupancy grid: more than 2^32 cells is not supported");
  }
}
constexpr std::size_t kBlock = 64;  // cells per entry of the free-cell index
constexpr std::size_t kGuide = 10;  // log2 of the free cells between guide entries

/// For every free cell k that is a multiple of 2^kGuide, the block holding it; then the number
/// of blocks. free_cell() searches only between two neighbouring entries.
std::vector<std::uint32_t> guide_free_cells(const std::vector<std::uint32_t>& before) {
  std::vector<std::uint32_t> guide;
  guide.reserve((before.back() >> kGuide) + 2);
  for (std::size_t b = 0; b + 1 < before.size(); ++b) {
    while ((static_cast<std::size_t>(guide.size()) << kGuide) < before[b + 1]) {
      guide.push_back(static_cast<std::uint32_t>(b));
    }
  }
  guide.push_back(static_cast<std::uint32_t>(before.size() - 1));
  return guide;
}

/// Free cells before each block of kBlock cells, and the total as the last entry: counted per
/// block in parallel, then a serial prefix sum (integers: the same for any thread count).
std::vector<std::uint32_t> count_free_cells(const std::vector<CellState>& cells) {
  const std::size_t blocks = (cells.size() + kBlock - 1) / kBlock;
  std::vector<std::uint32_t> before(blocks + 1);
  before[0] = 0;
  par::for_each_chunk(blocks, /*grain=*/1024, [&](std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t end = std::min(cells.size(), (b + 1) * kBlock);
      std::uint32_t n = 0;
      for (std::size_t k = b * kBlock; k < end; ++k) n += cells[k] == CellState::kFree ? 1U : 0U;
      before[b + 1] = n;
    }
  });
  for (std::size_t b = 0; b < blocks; ++b) before[b + 1] += before[b];
  return before;
}

}  // namespace

OccupancyGrid::OccupancyGrid(int width, int height, double resolution, Pose2 origin,
                             std::vector<CellState> cells)
    : width_(width),
      height_(height),
      resolution_(resolution),
      origin_(origin),
      cos_yaw_(std::cos(origin.theta)),
      sin_yaw_(std::sin(origin.theta)),
      cells_(std::move(cells)) {
  check_shape(width, height, resolution, cells_.size());
  free_before_ = count_free_cells(cells_);
  free_count_ = free_before_.back();
  free_guide_ = guide_free_cells(free_before_);
}

Point2 OccupancyGrid::to_grid_frame(Point2 world) const noexcept {
  const double dx = world.x - origin_.x;
  const double dy = world.y - origin_.y;
  return {cos_yaw_ * dx + sin_yaw_ * dy, -sin_yaw_ * dx + cos_yaw_ * dy};
}

Point2 OccupancyGrid::to_map_frame(Point2 grid) const noexcept {
  return {origin_.x + cos_yaw_ * grid.x - sin_yaw_ * grid.y,
          origin_.y + sin_yaw_ * grid.x + cos_yaw_ * grid.y};
}

CellIndex OccupancyGrid::world_to_cell(Point2 world) const noexcept {
  const Point2 g = to_grid_frame(world);
  // Clamp before converting so points far off the map never overflow int.
  const double limit = 1e9;
  const double ci = std::clamp(std::floor(g.x / resolution_), -limit, limit);
  const double cj = std::clamp(std::floor(g.y / resolution_), -limit, limit);
  return {static_cast<int>(ci), static_cast<int>(cj)};
}

Point2 OccupancyGrid::cell_center(CellIndex c) const noexcept {
  return to_map_frame({(c.i + 0.5) * resolution_, (c.j + 0.5) * resolution_});
}

std::uint32_t OccupancyGrid::free_cell(std::size_t k) const noexcept {
  // The last block with fewer than k + 1 free cells before it holds free cell k.
  const std::size_t g = k >> kGuide;
  const auto first = free_before_.begin() + free_guide_[g];
  const auto last = free_before_.begin() + free_guide_[g + 1] + 1;
  const auto after = std::upper_bound(first, last, k);
  const auto block = static_cast<std::size_t>(after - free_before_.begin()) - 1;
  std::size_t left = k - free_before_[block];
  std::size_t cell = block * kBlock;
  for (;; ++cell) {
    if (cells_[cell] != CellState::kFree) continue;
    if (left == 0) break;
    --left;
  }
  return static_cast<std::uint32_t>(cell);
}

std::vector<std::uint32_t> OccupancyGrid::free_cells() const {
  std::vector<std::uint32_t> free(free_count_);
  par::for_each_chunk(free_before_.size() - 1, /*grain=*/1024, [&](std::size_t b0, std::size_t b1) {
    std::uint32_t* out = free.data() + free_before_[b0];
    for (std::size_t k = b0 * kBlock; k < std::min(cells_.size(), b1 * kBlock); ++k) {
      if (cells_[k] == CellState::kFree) *out++ = static_cast<std::uint32_t>(k);
    }
  });
  return free;
}

Point2 OccupancyGrid::free_point(std::size_t k, double u, double v) const noexcept {
  return point_in_cell(free_cell(k), u, v);
}

Point2 OccupancyGrid::point_in_cell(std::uint32_t cell, double u, double v) const noexcept {
  const auto w = static_cast<std::uint32_t>(width_);
  const double gi = static_cast<double>(cell % w) + u;
  const double gj = static_cast<double>(cell / w) + v;
  return to_map_frame({gi * resolution_, gj * resolution_});
}

Bounds2 OccupancyGrid::bounds() const noexcept {
  const double w = width_ * resolution_;
  const double h = height_ * resolution_;
  Bounds2 b{origin_.x, origin_.y, origin_.x, origin_.y};
  for (const Point2 corner : {to_map_frame({w, 0}), to_map_frame({0, h}), to_map_frame({w, h})}) {
    b.min_x = std::min(b.min_x, corner.x);
    b.min_y = std::min(b.min_y, corner.y);
    b.max_x = std::max(b.max_x, corner.x);
    b.max_y = std::max(b.max_y, corner.y);
  }
  return b;
}

}  // namespace mote
