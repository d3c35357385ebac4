#include "ray_setup.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/core/parallel.hpp"

namespace mote::detail {

std::vector<std::uint8_t> blocking_mask(const OccupancyGrid& grid, bool unknown_blocks) {
  std::vector<std::uint8_t> mask;
  huge_pages::reserve(mask, grid.cell_count());
  mask.resize(grid.cell_count());
  const CellState* cells = grid.cells().data();
  par::for_each_chunk(mask.size(), /*grain=*/std::size_t{1} << 20U,
                      [&](std::size_t begin, std::size_t end) {
                        for (std::size_t k = begin; k < end; ++k) {
                          const bool blocks = cells[k] == CellState::kOccupied ||
                                              (unknown_blocks && cells[k] == CellState::kUnknown);
                          mask[k] = blocks ? 1 : 0;
                        }
                      });
  return mask;
}

int CellMask::cell_of(double v, int count) const noexcept {
  // Written so that NaN compares false and lands off the map.
  if (!(v >= line(0))) return -1;
  if (!(v < line(count))) return count;
  int k = static_cast<int>(std::floor(v / static_cast<double>(resolution)));
  k = std::clamp(k, 0, count - 1);
  // The division may round across a line; the float lattice decides.
  while (k > 0 && v < line(k)) --k;
  while (k + 1 < count && v >= line(k + 1)) ++k;
  return k;
}

double CellMask::snap_to_line(double v, int count) const noexcept {
  const int k = std::clamp(cell_of(v, count), 0, count);
  for (const int line_index : {k, k + 1}) {
    if (std::abs(v - line(line_index)) <= kSnapDistance) return line(line_index);
  }
  return static_cast<double>(static_cast<float>(v));
}

GridRay CellMask::prepare(const GridRay& r) const noexcept {
  return {snap_to_line(r.ox, width), snap_to_line(r.oy, height), snap_direction(r.dx),
          snap_direction(r.dy)};
}

bool CellMask::blocks_start(double gx, double gy) const noexcept {
  const int i = cell_of(gx, width);
  const int j = cell_of(gy, height);
  const bool on_column_line = i >= 0 && i <= width && line(i) == gx;
  const bool on_row_line = j >= 0 && j <= height && line(j) == gy;
  return blocks_or_free(i, j) || (on_column_line && blocks_or_free(i - 1, j)) ||
         (on_row_line && blocks_or_free(i, j - 1)) ||
         (on_column_line && on_row_line && blocks_or_free(i - 1, j - 1));
}

GridFrame::GridFrame(const Pose2& origin) noexcept
    : origin_(origin), c_(std::cos(origin.theta)), s_(std::sin(origin.theta)) {}

Point2 GridFrame::to_grid(double x, double y) const noexcept {
  const double dx = x - origin_.x;
  const double dy = y - origin_.y;
  return {c_ * dx + s_ * dy, -s_ * dx + c_ * dy};
}

GridRay GridFrame::ray(Point2 origin, double angle) const noexcept {
  const Point2 g = to_grid(origin.x, origin.y);
  const double a = angle - origin_.theta;
  return {g.x, g.y, std::cos(a), std::sin(a)};
}

void check_max_range(float max_range) {
  if (!(max_range > 0.0F) || !std::isfinite(max_range)) {
    throw ConfigError("ray cast: max_range must be a positive number of metres, got " +
                      std::to_string(max_range));
  }
}

namespace {
void check_batch(const RayBatch& batch, std::size_t ranges_size) {
  if (batch.y.size() != batch.x.size() || batch.theta.size() != batch.x.size()) {
    throw ConfigError("ray cast: x, y and theta must hold one value per particle (got " +
                      std::to_string(batch.x.size()) + ", " + std::to_string(batch.y.size()) +
                      ", " + std::to_string(batch.theta.size()) + ")");
  }
  if (ranges_size != batch.ray_count()) {
    throw ConfigError(
        "ray cast: ranges must hold particles * beams = " + std::to_string(batch.ray_count()) +
        " values, got " + std::to_string(ranges_size));
  }
  check_max_range(batch.max_range);
  if (!is_finite(batch.sensor_offset)) {
    throw ConfigError("ray cast: the sensor offset must be finite");
  }
}
}  // namespace

BatchRays::BatchRays(const GridFrame& frame, const CellMask& mask, const RayBatch& batch,
                     std::size_t ranges_size)
    : frame_(frame), mask_(mask), batch_(batch) {
  check_batch(batch, ranges_size);
  beam_cos_.reserve(batch.beam_count());
  beam_sin_.reserve(batch.beam_count());
  for (const float angle : batch.beam_angles) {
    if (!std::isfinite(angle)) throw ConfigError("ray cast: beam angles must be finite");
    beam_cos_.push_back(std::cos(static_cast<double>(angle)));
    beam_sin_.push_back(std::sin(static_cast<double>(angle)));
  }
}

SensorFrame BatchRays::sensor(std::size_t particle) const noexcept {
  const double px = batch_.x[particle];
  const double py = batch_.y[particle];
  const double pt = batch_.theta[particle];
  // Sensor pose = particle pose (+) mounting offset (Thrun table 6.3, the sensor's x_k,sens), then
  // the grid frame; the heading is taken relative to the grid's yaw.
  const Pose2& off = batch_.sensor_offset;
  const double pc = std::cos(pt);
  const double ps = std::sin(pt);
  const Point2 g = frame_.to_grid(px + pc * off.x - ps * off.y, py + ps * off.x + pc * off.y);
  const double heading = pt + off.theta - frame_.origin().theta;
  SensorFrame f{mask_.snap_to_line(g.x, mask_.width), mask_.snap_to_line(g.y, mask_.height),
                std::cos(heading), std::sin(heading), true};
  f.finite = std::isfinite(f.ox) && std::isfinite(f.oy) && std::isfinite(f.c);
  return f;
}

}  // namespace mote::detail
