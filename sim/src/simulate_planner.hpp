#pragma once
/// \file
/// Path planning for the simulator: cells with enough clearance from every blocking cell,
/// breadth-first search over them (8-connected, no corner cutting) and line-of-sight shortening
/// of the cell path into a polyline of map frame waypoints.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mote/core/free_space.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote::sim::detail {

/// Which cells of a grid have at least `radius` metres of free space around their centre.
/// Occupied, unknown and off-grid cells all block.
class ClearanceMask {
 public:
  ClearanceMask(const OccupancyGrid& grid, double radius);

  /// True when the cell lies on the grid and no blocking cell is within the radius.
  [[nodiscard]] bool clear(CellIndex c) const noexcept {
    return grid_->contains(c) && clear_[grid_->linear_index(c)] != 0;
  }
  /// True when the map frame point's cell is clear.
  [[nodiscard]] bool clear(Point2 p) const noexcept { return clear(grid_->world_to_cell(p)); }
  /// True when every point of the segment a-b (sampled at a quarter cell) lies in a clear cell.
  [[nodiscard]] bool segment_clear(Point2 a, Point2 b) const noexcept;
  [[nodiscard]] const OccupancyGrid& grid() const noexcept { return *grid_; }

 private:
  void block_around(CellIndex c, const std::vector<CellIndex>& offsets);

  const OccupancyGrid* grid_;
  std::vector<std::uint8_t> clear_;
};

/// Plans collision-free paths through the clear cells of a mask.
class PathPlanner {
 public:
  explicit PathPlanner(const ClearanceMask& mask) : mask_(&mask) {}

  /// Linear indices of the cells reachable from `start` (start itself included even when it is
  /// not clear, so a robot that starts close to a wall can still leave).
  [[nodiscard]] std::vector<std::uint32_t> reachable(CellIndex start) const;

  /// Linear indices of the largest 8-connected set of clear cells; empty when none is clear.
  [[nodiscard]] std::vector<std::uint32_t> largest_region() const;

  /// Waypoints (map frame, m) from `from` to the centre of `goal`, shortened by line of sight;
  /// the first waypoint is `from`. Empty when the goal cannot be reached.
  [[nodiscard]] std::vector<Point2> plan(Point2 from, CellIndex goal) const;

 private:
  /// Breadth-first search from `start`; parent[k] = linear index of the predecessor of cell k,
  /// kNone when unvisited. Stops early when `goal` is reached.
  [[nodiscard]] std::vector<std::uint32_t> search(CellIndex start, std::size_t goal) const;
  [[nodiscard]] std::vector<Point2> shorten(const std::vector<std::uint32_t>& cells,
                                            Point2 from) const;
  [[nodiscard]] CellIndex cell_of(std::uint32_t k) const noexcept;

  const ClearanceMask* mask_;
};

}  // namespace mote::sim::detail
