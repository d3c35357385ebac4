/// \file
/// Clearance mask, breadth-first path search and line-of-sight shortening for the simulator.

#include "simulate_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mote::sim::detail {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// Offsets of the cells whose nearest point lies closer than `radius` (m) to a cell centre.
std::vector<CellIndex> disc_offsets(double radius, double resolution) {
  const int reach = static_cast<int>(std::ceil(radius / resolution + 0.5));
  std::vector<CellIndex> offsets;
  for (int dj = -reach; dj <= reach; ++dj) {
    for (int di = -reach; di <= reach; ++di) {
      const double gx = std::max(0.0, std::abs(di) - 0.5) * resolution;
      const double gy = std::max(0.0, std::abs(dj) - 0.5) * resolution;
      if (std::hypot(gx, gy) < radius) offsets.push_back({di, dj});
    }
  }
  return offsets;
}

/// Calls f(neighbour) for the 8 neighbours of c that are clear; a diagonal step needs both
/// cells beside it clear, so a path never squeezes between two blocked corners.
template <class F>
void for_each_step(const ClearanceMask& mask, CellIndex c, F&& f) {
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      if (di == 0 && dj == 0) continue;
      const CellIndex n{c.i + di, c.j + dj};
      if (!mask.clear(n)) continue;
      if (di != 0 && dj != 0 &&
          !(mask.clear(CellIndex{c.i + di, c.j}) && mask.clear(CellIndex{c.i, c.j + dj}))) {
        continue;
      }
      f(n);
    }
  }
}

}  // namespace

ClearanceMask::ClearanceMask(const OccupancyGrid& grid, double radius)
    : grid_(&grid), clear_(grid.cell_count(), 1) {
  const double res = grid.resolution();
  const std::vector<CellIndex> offsets = disc_offsets(radius, res);
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      const CellIndex c{i, j};
      if (grid.at(c) != CellState::kFree) block_around(c, offsets);
      // Off-grid space blocks too: the grid edge lies (i + 0.5) cells from the centre.
      const double edge =
          std::min({i + 0.5, grid.width() - i - 0.5, j + 0.5, grid.height() - j - 0.5}) * res;
      if (edge < radius) clear_[grid.linear_index(c)] = 0;
    }
  }
}

void ClearanceMask::block_around(CellIndex c, const std::vector<CellIndex>& offsets) {
  for (const CellIndex& o : offsets) {
    const CellIndex n{c.i + o.i, c.j + o.j};
    if (grid_->contains(n)) clear_[grid_->linear_index(n)] = 0;
  }
}

bool ClearanceMask::segment_clear(Point2 a, Point2 b) const noexcept {
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int steps = static_cast<int>(std::ceil(4.0 * length / grid_->resolution())) + 1;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    if (!clear(Point2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)})) return false;
  }
  return true;
}

CellIndex PathPlanner::cell_of(std::uint32_t k) const noexcept {
  const int w = mask_->grid().width();
  return {static_cast<int>(k % static_cast<std::uint32_t>(w)),
          static_cast<int>(k / static_cast<std::uint32_t>(w))};
}

std::vector<std::uint32_t> PathPlanner::search(CellIndex start, std::size_t goal) const {
  const OccupancyGrid& grid = mask_->grid();
  std::vector<std::uint32_t> parent(grid.cell_count(), kNone);
  if (!grid.contains(start)) return parent;
  const auto s = static_cast<std::uint32_t>(grid.linear_index(start));
  parent[s] = s;
  std::vector<std::uint32_t> queue{s};
  for (std::size_t head = 0; head < queue.size() && queue[head] != goal; ++head) {
    const std::uint32_t k = queue[head];
    for_each_step(*mask_, cell_of(k), [&](CellIndex n) {
      const auto m = static_cast<std::uint32_t>(grid.linear_index(n));
      if (parent[m] != kNone) return;
      parent[m] = k;
      queue.push_back(m);
    });
  }
  return parent;
}

std::vector<std::uint32_t> PathPlanner::reachable(CellIndex start) const {
  const std::vector<std::uint32_t> parent = search(start, std::numeric_limits<std::size_t>::max());
  std::vector<std::uint32_t> cells;
  for (std::size_t k = 0; k < parent.size(); ++k) {
    if (parent[k] != kNone) cells.push_back(static_cast<std::uint32_t>(k));
  }
  return cells;
}

std::vector<std::uint32_t> PathPlanner::largest_region() const {
  const OccupancyGrid& grid = mask_->grid();
  std::vector<std::uint8_t> seen(grid.cell_count(), 0);
  std::vector<std::uint32_t> best;
  std::vector<std::uint32_t> region;
  for (std::uint32_t k = 0; k < grid.cell_count(); ++k) {
    if (seen[k] != 0 || !mask_->clear(cell_of(k))) continue;
    region.assign(1, k);
    seen[k] = 1;
    for (std::size_t head = 0; head < region.size(); ++head) {
      for_each_step(*mask_, cell_of(region[head]), [&](CellIndex n) {
        const auto m = static_cast<std::uint32_t>(grid.linear_index(n));
        if (seen[m] == 0) {
          seen[m] = 1;
          region.push_back(m);
        }
      });
    }
    if (region.size() > best.size()) best.swap(region);
  }
  std::sort(best.begin(), best.end());
  return best;
}

std::vector<Point2> PathPlanner::plan(Point2 from, CellIndex goal) const {
  const OccupancyGrid& grid = mask_->grid();
  if (!mask_->clear(goal)) return {};
  const std::size_t g = grid.linear_index(goal);
  const std::vector<std::uint32_t> parent = search(grid.world_to_cell(from), g);
  if (parent[g] == kNone) return {};
  std::vector<std::uint32_t> cells{static_cast<std::uint32_t>(g)};
  while (parent[cells.back()] != cells.back()) cells.push_back(parent[cells.back()]);
  std::reverse(cells.begin(), cells.end());
  return shorten(cells, from);
}

std::vector<Point2> PathPlanner::shorten(const std::vector<std::uint32_t>& cells,
                                         Point2 from) const {
  // Greedy string pulling: from each waypoint, go straight to the last cell of the search path
  // that is still in clear line of sight.
  const OccupancyGrid& grid = mask_->grid();
  std::vector<Point2> path{from};
  std::size_t next = 1;
  while (next < cells.size()) {
    std::size_t reach = next;
    while (reach + 1 < cells.size() &&
           mask_->segment_clear(path.back(), grid.cell_center(cell_of(cells[reach + 1])))) {
      ++reach;
    }
    path.push_back(grid.cell_center(cell_of(cells[reach])));
    next = reach + 1;
  }
  if (cells.size() == 1) path.push_back(grid.cell_center(cell_of(cells[0])));
  return path;
}

}  // namespace mote::sim::detail
