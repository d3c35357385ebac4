#pragma once
/// \file
/// Hand-built grids for the ray casting tests, with geometry simple enough to know every range.

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

}  // namespace mote::test
