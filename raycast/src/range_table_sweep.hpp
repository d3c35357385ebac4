#pragma once
/// \file
/// Internal: the directional sweep that fills one direction of the range table.

#include <cstdint>
#include <span>
#include <vector>

#include "ray_setup.hpp"

namespace mote::detail {

/// Range entry of a ray that leaves the map without meeting a blocking cell. 15 bits, as when
/// the top bit flagged certification (removed): the units per cell, and so the ranges, stay
/// those measured in BENCHMARKS.md.
inline constexpr std::uint16_t kNoHit = 0x7FFFU;
/// Lines per lattice step: the nearest line passes within half this of every lattice point.
inline constexpr double kLineSpacing = 0.25;

/// Reused between directions by one build task.
struct SweepScratch {
  int first_line = 0;                     ///< the first line holding a point
  std::vector<std::uint32_t> line_start;  ///< points of line first_line + k: order[[k], [k + 1])
  std::vector<std::uint32_t> order;       ///< slots bucketed by line
  std::vector<int> line_of;               ///< nearest line of each slot
  std::vector<double> along;              ///< position of each slot along its line
  std::vector<double> hits;
};

/// Fills column[slot] with the range (units_per_cell units per cell) from lattice point slot,
/// at (px[slot], py[slot]) cells, along direction (dx, dy), a unit vector in the grid frame.
///
/// One pass per direction instead of one ray per entry: the points are bucketed onto lines
/// parallel to the direction, kLineSpacing lattice steps apart; each line is walked once
/// (Amanatides-Woo) from its first point to the first blocking cell beyond its last, collecting
/// where it enters blocking cells, and every point takes the first entry beyond it. A direction
/// costs O(points + cells crossed), whatever the ranges; the nearest line passing within
/// kLineSpacing / 2 lattice steps of the point is the build's only approximation.
void sweep_direction(const CellMask& mask, std::span<const float> px, std::span<const float> py,
                     double lattice, double dx, double dy, double units_per_cell,
                     SweepScratch& scratch, std::span<std::uint16_t> column);

}  // namespace mote::detail
