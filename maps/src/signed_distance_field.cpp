#include "mote/maps/signed_distance_field.hpp"

#include <algorithm>
#include <cmath>

#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/core/parallel.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/squared_distances.hpp"

namespace mote {
namespace {

// Codes hold 2 cap + 2 values in 16 bits: cap = n^2 <= 32767.
constexpr int kMaxCodeSaturation = 181;

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
  const int n = SquaredDistances::saturation(resolution_, max_distance + half, kMaxCodeSaturation);
  if (n > 0) {
    build_codes(grid, n);
  } else {
    build_floats(grid);
  }
}

void SignedDistanceField::build_codes(const OccupancyGrid& grid, int saturation) {
  const auto half = static_cast<float>(0.5 * resolution_);
  const float clamp = max_distance_ + half;
  const auto cap = static_cast<std::uint32_t>(saturation * saturation);
  // DistanceField's value of a squared distance s at a clamp.
  const auto distance = [&](std::uint32_t s, float at) {
    return std::min(static_cast<float>(std::sqrt(static_cast<double>(s)) * resolution_), at);
  };
  signed_of_.resize(2 * static_cast<std::size_t>(cap) + 2);
  unsigned_of_.resize(signed_of_.size());
  for (std::uint32_t s = 0; s <= cap; ++s) {
    signed_of_[s] = std::min(distance(s, clamp) - half, max_distance_);
    unsigned_of_[s] = distance(s, max_distance_);
    signed_of_[cap + 1 + s] = -std::min(distance(s, clamp) - half, max_distance_);
    unsigned_of_[cap + 1 + s] = 0.0F;
  }
  // Two transforms straight into the codes, a band of rows at a time: the first writes every
  // cell, the second overwrites the occupied ones with their depth.
  const auto w = static_cast<std::size_t>(width_);
  codes_ = huge_pages::uninitialized<std::uint16_t>(grid.cell_count());
  for_each_squared_row(
      grid, ObstacleCells::kOccupied, saturation,
      [&](std::size_t j, std::size_t i0, std::size_t count, const std::uint16_t* s) {
        std::copy(s, s + count, codes_.get() + j * w + i0);
      });
  const CellState* states = grid.cells().data();
  for_each_squared_row(
      grid, ObstacleCells::kNotOccupied, saturation,
      [&](std::size_t j, std::size_t i0, std::size_t count, const std::uint16_t* s) {
        std::uint16_t* row = codes_.get() + j * w + i0;
        const CellState* state = states + j * w + i0;
        for (std::size_t i = 0; i < count; ++i) {
          if (state[i] == CellState::kOccupied) {
            row[i] = static_cast<std::uint16_t>(cap + 1 + s[i]);
          }
        }
      });
}

void SignedDistanceField::build_floats(const OccupancyGrid& grid) {
  const auto half = static_cast<float>(0.5 * resolution_);
  const DistanceField out(grid,
                          {.unknown_is_obstacle = false, .max_distance = max_distance_ + half});
  const DistanceField in(inside_out(grid),
                         {.unknown_is_obstacle = true, .max_distance = max_distance_ + half});
  const DistanceField plain(grid, {.unknown_is_obstacle = false, .max_distance = max_distance_});
  const std::vector<CellState>& cells = grid.cells();
  values_.resize(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    values_[k] = cells[k] == CellState::kOccupied
                     ? -std::min(in.distances()[k] - half, max_distance_)
                     : std::min(out.distances()[k] - half, max_distance_);
  }
  unsigned_ = plain.distances();
}

}  // namespace mote
