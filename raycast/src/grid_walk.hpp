#pragma once
/// \file
/// Internal: the exact cell walk behind GridRayCaster.

#include "ray_setup.hpp"

namespace mote::detail {

/// Range (m) along a grid frame ray (already rounded to float) to the first wall, or max_range.
/// A wall is any boundary between a blocking and a non-blocking cell, extended by kSnapDistance
/// past its ends like the Embree walls: a ray through a cell corner stops if a wall ends there,
/// and a ray running exactly along a grid line stops where a wall crosses or touches the line.
/// The caller has already applied the start rule (CellMask::blocks_start).
[[nodiscard]] float walk_grid(const CellMask& mask, const GridRay& ray, float max_range);

}  // namespace mote::detail
