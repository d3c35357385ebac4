#pragma once
/// \file
/// Hand-built grids for the ray casting tests, with geometry simple enough to know every range.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "mote/maps/occupancy_grid.hpp"

namespace mote::test {

/// A grid drawn as text, top row first: '#' occupied, '.' free, '?' unknown.
inline OccupancyGrid grid_from_rows(const std::vector<std::string>& rows, double resolution,
                                    Pose2 origin = {}) {
  const int height = static_cast<int>(rows.size());
  const int width = static_cast<int>(rows.front().size());
  std::vector<CellState> cells;
  for (int j = 0; j < height; ++j) {
    for (const char c : rows[static_cast<std::size_t>(height - 1 - j)]) {
      cells.push_back(c == '#'   ? CellState::kOccupied
                      : c == '?' ? CellState::kUnknown
                                 : CellState::kFree);
    }
  }
  return {width, height, resolution, origin, std::move(cells)};
}

/// A 10 x 10 room of 0.5 m cells: a one-cell wall ring around a free 8 x 8 interior, so the
/// inner faces sit at 0.5 m and 4.5 m in the grid frame.
inline OccupancyGrid box_room(Pose2 origin = {}) {
  std::vector<std::string> rows(10, "#........#");
  rows.front() = rows.back() = "##########";
  return grid_from_rows(rows, 0.5, origin);
}

/// Sensor poses scattered uniformly over a map's free cells, headings uniform; every
/// `off_free_every`-th one moved 0.5 m in x, so that some start outside free cells (0: none).
struct Scatter {
  std::vector<float> x, y, theta;
};

inline Scatter scatter_in_free_cells(const OccupancyGrid& grid, int count, std::uint64_t seed,
                                     int off_free_every = 0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto& free = grid.free_cells();
  Scatter s;
  for (int i = 0; i < count; ++i) {
    const auto f = static_cast<std::size_t>(u(rng) * static_cast<double>(free.size()));
    const Point2 p = grid.free_point(std::min(f, free.size() - 1), u(rng), u(rng));
    const bool off = off_free_every > 0 && i % off_free_every == 0;
    s.x.push_back(static_cast<float>(p.x + (off ? 0.5 : 0.0)));
    s.y.push_back(static_cast<float>(p.y));
    s.theta.push_back(static_cast<float>((2.0 * u(rng) - 1.0) * std::numbers::pi));
  }
  return s;
}

}  // namespace mote::test
