#pragma once
/// \file
/// Internal: the exact cell walk behind GridRayCaster.

#include "ray_setup.hpp"

namespace mote::detail {

/// Range (m) along a grid frame ray (already rounded to float) to the first wall, or max_range.
/// A wall is any boundary between a blocking and a non-blocking cell, and a ray that touches a
/// wall stops there, as Embree's watertight test counts hits on quad edges: a ray through a
/// cell corner stops if any cell around the corner blocks, and a ray running exactly along a
/// grid line stops where either neighbouring row (or column) changes state.
[[nodiscard]] float walk_grid(const CellMask& mask, const GridRay& ray, float max_range);

}  // namespace mote::detail
