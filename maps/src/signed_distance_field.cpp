#include "mote/maps/signed_distance_field.hpp"

#include <algorithm>
#include <cmath>

#include "mote/core/error.hpp"
#include "mote/maps/distance_field.hpp"

namespace mote {
namespace {

// The grid with occupied and free swapped: its distance transform, with unknown cells as
// obstacles, measures how deep each occupied cell lies inside its obstacle.
OccupancyGrid inside_out(const OccupancyGrid& grid) {
  std::vector<CellState> cells = grid.cells();
  for (CellState& c : cells) {
    if (c == CellState::kOccupied) {
      c = CellState::kFree;
    } else if (c == CellState::kFree) {
      c = CellState::kOccupied;
    }
  }
  return {grid.width(), grid.height(), grid.resolution(), grid.origin(), std::move(cells)};
}

}  // namespace

SignedDistanceField::SignedDistanceField(const OccupancyGrid& grid, float max_distance)
    : width_(grid.width()),
      height_(grid.height()),
      resolution_(grid.resolution()),
      origin_(grid.origin()),
      max_distance_(max_distance) {
  if (!(max_distance > 0.0F)) {
    throw ConfigError("SignedDistanceField: max_distance must be positive");
  }
  // Distances run between cell centres; the surface lies half a cell from the centres on
  // either side of it. The transforms clamp half a cell further, so that the clamp applies to
  // the distance to the surface.
  const auto half = static_cast<float>(0.5 * resolution_);
  const DistanceField out(grid,
                          {.unknown_is_obstacle = false, .max_distance = max_distance + half});
  const DistanceField in(inside_out(grid),
                         {.unknown_is_obstacle = true, .max_distance = max_distance + half});
  const std::vector<CellState>& cells = grid.cells();
  values_.resize(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    values_[k] = cells[k] == CellState::kOccupied
                     ? -std::min(in.distances()[k] - half, max_distance)
                     : std::min(out.distances()[k] - half, max_distance);
  }
}

}  // namespace mote
