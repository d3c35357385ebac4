#pragma once
/// \file
/// A precomputed likelihood field (Thrun et al., Probabilistic Robotics, table 6.3): one float
/// per cell, f(distance to the nearest obstacle), surrounded by a ring of `outside` cells so
/// that a beam endpoint anywhere, even far off the map, reads a valid cell without a branch.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "mote/maps/distance_field.hpp"
#include "mote/maps/squared_distances.hpp"

namespace mote {

/// Map frame (x, y) in metres to fractional table (col, row), all float for vector code:
/// col = ( cos_yaw (x - origin_x) + sin_yaw (y - origin_y)) * inv_resolution + border,
/// row = (-sin_yaw (x - origin_x) + cos_yaw (y - origin_y)) * inv_resolution + border.
/// Grid cell (i, j) is table cell (i + border, j + border).
struct TableTransform {
  float cos_yaw = 1.0F;         ///< cos of the map origin's yaw
  float sin_yaw = 0.0F;         ///< sin of the map origin's yaw
  float origin_x = 0.0F;        ///< map origin, m
  float origin_y = 0.0F;        ///< map origin, m
  float inv_resolution = 1.0F;  ///< cells per m
  float border = 1.0F;          ///< ring width, cells
  float max_col = 0.0F;         ///< last table column, as a float clamp bound
  float max_row = 0.0F;         ///< last table row, as a float clamp bound
};

/// The table as plain values: what a vectorized sensor-model loop needs.
struct LikelihoodView {
  const float* data = nullptr;  ///< row-major from the bottom table row
  std::int32_t stride = 0;      ///< floats per table row (the whole table fits int32 indices)
  TableTransform transform;

  /// The value at a map frame point, m. Branch-free: the fractional index is clamped into
  /// [0, max] before truncation, so any point off the map (also inf or NaN) reads a border
  /// cell. `a > b ? a : b` compiles to maxss/vmaxps, which returns b for NaN.
  [[nodiscard]] float lookup(float x, float y) const noexcept {
    const TableTransform& t = transform;
    const float dx = x - t.origin_x;
    const float dy = y - t.origin_y;
    return at_cell((t.cos_yaw * dx + t.sin_yaw * dy) * t.inv_resolution + t.border,
                   (t.cos_yaw * dy - t.sin_yaw * dx) * t.inv_resolution + t.border);
  }

  /// The value at fractional table cell (col, row), for callers that transform into table
  /// cells themselves. Clamped like lookup(): any col and row, also inf or NaN, are safe.
  [[nodiscard]] float at_cell(float col, float row) const noexcept {
    const TableTransform& t = transform;
    col = col > 0.0F ? col : 0.0F;
    row = row > 0.0F ? row : 0.0F;
    col = col < t.max_col ? col : t.max_col;
    row = row < t.max_row ? row : t.max_row;
    // 32-bit index arithmetic lets GCC vectorize the loop (with int64 math it gives up).
    return data[static_cast<std::int32_t>(row) * stride + static_cast<std::int32_t>(col)];
  }
};

/// f(distance) over the grid plus a border ring holding `outside`.
class LikelihoodTable {
 public:
  /// f maps a distance in m (possibly +inf, on a map without obstacles) to the stored value,
  /// e.g. log(z_hit * gaussian(d) + z_random / z_max). border >= 1 cells; throws ConfigError
  /// otherwise.
  LikelihoodTable(const DistanceField& field, const std::function<float(float)>& f, float outside,
                  int border = 1);
  /// The same table from the compact transform: f runs once per squared distance up to
  /// field.cap() (a few hundred calls, not one per cell), each cell copies its value; equal
  /// bit for bit to the table of the DistanceField with the same clamp.
  LikelihoodTable(const SquaredDistances& field, const std::function<float(float)>& f,
                  float outside, int border = 1);
  /// The same table straight from the grid (for_each_squared_row): f of the distance to the
  /// nearest of `obstacles`, clamped at `clamp` m, with nothing grid-sized but the table
  /// allocated. Throws ConfigError unless the clamp fits SquaredDistances.
  LikelihoodTable(const OccupancyGrid& grid, ObstacleCells obstacles, float clamp,
                  const std::function<float(float)>& f, float outside, int border = 1);

  [[nodiscard]] int width() const noexcept { return width_; }    ///< grid width + 2 border
  [[nodiscard]] int height() const noexcept { return height_; }  ///< grid height + 2 border
  [[nodiscard]] int border() const noexcept { return border_; }
  [[nodiscard]] std::size_t stride() const noexcept { return stride_; }  ///< floats per row
  [[nodiscard]] float outside() const noexcept { return outside_; }
  /// Row-major from the bottom table row; width() valid floats per stride().
  [[nodiscard]] const float* data() const noexcept { return values_.get(); }
  [[nodiscard]] const TableTransform& transform() const noexcept { return transform_; }

  /// The value of grid cell c (inside the grid).
  [[nodiscard]] float at(CellIndex c) const noexcept {
    return values_[static_cast<std::size_t>(c.j + border_) * stride_ +
                   static_cast<std::size_t>(c.i + border_)];
  }

  /// A copyable view for hot loops (see LikelihoodView::lookup).
  [[nodiscard]] LikelihoodView view() const noexcept {
    return {values_.get(), static_cast<std::int32_t>(stride_), transform_};
  }
  /// The value at a map frame point, m (see LikelihoodView::lookup). In a loop over many
  /// points, copy view() into a local first so the compiler can keep it in registers.
  [[nodiscard]] float lookup(float x, float y) const noexcept { return view().lookup(x, y); }

 private:
  /// Geometry of a grid of width x height cells at resolution and origin, border ring filled.
  LikelihoodTable(int width, int height, double resolution, const Pose2& origin, float outside,
                  int border);
  /// Fills grid row j (without the ring) by value(i), in parallel over rows.
  template <typename Value>
  void fill_rows(const Value& value);

  int width_;
  int height_;
  int border_;
  std::size_t stride_;
  float outside_;
  TableTransform transform_;
  std::unique_ptr<float[]> values_;  // 4 bytes per cell; the ring written once, no zeroing
};

}  // namespace mote
