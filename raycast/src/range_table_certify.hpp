#pragma once
/// \file
/// Internal: marks the range table entries whose range cannot be trusted within a cell for every
/// sensor position and ray angle a query maps to them, so that those rays are cast exactly.

#include <cstdint>
#include <span>

#include "range_table_layout.hpp"

namespace mote::detail {

/// What certification reads: the table and the geometry of its lattice and directions.
struct CertifyInput {
  const TableLayout& layout;
  std::span<const float> point_x;  ///< cells, lattice point of each slot
  std::span<const float> point_y;
  std::span<const float> cos_a;  ///< direction of each table angle, grid frame
  std::span<const float> sin_a;
  double units_per_cell = 8.0;
  double tolerance_cells = 1.0;  ///< largest disagreement an entry may vouch for
};

/// Sets kUncertified on entry (p, k) of ranges (row-major, one row of angles per slot), which
/// answers for the angles from k to k + 1 (a query interpolates between them), unless
///  - the second differences of p's ranges over angle at k and at k + 1 are at most the
///    tolerance (no jump between neighbouring directions; a slanted wall's smooth change is
///    what interpolation follows), and
///  - every lattice neighbour of p within a lattice step beside its ray reaches the same wall
///    along direction k: its hit, moved onto p's ray, lies within the tolerance of p's, scaled
///    by how much farther beside the ray it is than a query's origin can be (half a step).
/// Parallel over slots, each writing its own row: the result is the same for any thread count.
/// Returns how many entries it marked.
std::size_t certify(const CertifyInput& in, std::span<std::uint16_t> ranges);

}  // namespace mote::detail
