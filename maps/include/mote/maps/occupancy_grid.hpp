#pragma once
/// \file
/// A 2D occupancy grid in the ROS map_server convention: cell (0, 0) is the lower-left cell, its
/// lower-left corner sits at `origin` (x, y, yaw) in the map frame; column i grows along the
/// origin's x axis and row j along its y axis, each cell `resolution` metres wide.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "mote/core/free_space.hpp"
#include "mote/core/pose.hpp"

namespace mote {

/// What a cell holds, with map_server's rules (occupied above occupied_thresh, free below
/// free_thresh, unknown in between).
enum class CellState : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

/// Integer cell coordinates: i is the column (grid x), j the row (grid y, 0 at the bottom).
struct CellIndex {
  int i = 0;
  int j = 0;
  friend bool operator==(const CellIndex&, const CellIndex&) = default;
};

/// An occupancy grid with world-to-cell transforms and an index of its free cells: the count of
/// free cells before every block of 64 cells (1/16 byte per cell), from which free_point() finds
/// the k-th free cell by a binary search (between the blocks of free cells 1024 apart) and a
/// scan of one block.
class OccupancyGrid final : public FreeSpace {
 public:
  /// cells holds width * height states, row-major from the bottom row (j = 0) up.
  /// Throws ConfigError on non-positive sizes or resolution, or a wrong number of cells.
  OccupancyGrid(int width, int height, double resolution, Pose2 origin,
                std::vector<CellState> cells);

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] double resolution() const noexcept { return resolution_; }  ///< m per cell
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }
  [[nodiscard]] std::size_t cell_count() const noexcept { return cells_.size(); }

  [[nodiscard]] bool contains(CellIndex c) const noexcept {
    return c.i >= 0 && c.j >= 0 && c.i < width_ && c.j < height_;
  }
  /// Row-major index of a cell inside the grid.
  [[nodiscard]] std::size_t linear_index(CellIndex c) const noexcept {
    return static_cast<std::size_t>(c.j) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(c.i);
  }
  /// State of a cell inside the grid (contains(c) must hold).
  [[nodiscard]] CellState at(CellIndex c) const noexcept { return cells_[linear_index(c)]; }
  /// State of a cell, or `outside` when the cell is off the grid.
  [[nodiscard]] CellState at_or(CellIndex c, CellState outside) const noexcept {
    return contains(c) ? at(c) : outside;
  }
  /// Every cell, row-major from the bottom row.
  [[nodiscard]] const std::vector<CellState>& cells() const noexcept { return cells_; }

  /// A map frame point in the grid's own frame (origin at the lower-left corner, axes along
  /// the grid), m.
  [[nodiscard]] Point2 to_grid_frame(Point2 world) const noexcept;
  /// A grid frame point back into the map frame.
  [[nodiscard]] Point2 to_map_frame(Point2 grid) const noexcept;
  /// The cell holding a map frame point (may lie off the grid: check contains()).
  [[nodiscard]] CellIndex world_to_cell(Point2 world) const noexcept;
  /// Centre of a cell in the map frame.
  [[nodiscard]] Point2 cell_center(CellIndex c) const noexcept;
  /// The map frame point at fractions (u, v) in [0, 1) across the cell of linear index `cell`.
  [[nodiscard]] Point2 point_in_cell(std::uint32_t cell, double u, double v) const noexcept;

  // FreeSpace
  [[nodiscard]] std::size_t free_cell_count() const noexcept override { return free_count_; }
  [[nodiscard]] Point2 free_point(std::size_t k, double u, double v) const noexcept override;
  [[nodiscard]] Bounds2 bounds() const noexcept override;
  /// Linear indices of the free cells, ascending, listed on each call (4 bytes per free cell).
  [[nodiscard]] std::vector<std::uint32_t> free_cells() const;
  /// Linear index of the k-th free cell (k < free_cell_count()).
  [[nodiscard]] std::uint32_t free_cell(std::size_t k) const noexcept;

 private:
  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  double cos_yaw_;
  double sin_yaw_;
  std::vector<CellState> cells_;
  std::vector<std::uint32_t> free_before_;  // free cells before each 64-cell block
  std::vector<std::uint32_t> free_guide_;   // the block of every 1024th free cell
  std::size_t free_count_ = 0;
};

}  // namespace mote
