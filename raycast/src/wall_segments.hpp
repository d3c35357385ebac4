#pragma once
/// \file
/// Internal: the boundary between blocking and non-blocking cells as maximal axis-aligned
/// segments, in the grid frame. Off-map space counts as non-blocking, so blocking cells on the
/// border get their outer edge too.

#include <vector>

#include "ray_setup.hpp"

namespace mote::detail {

/// A wall segment from (x0, y0) to (x1, y1), grid frame, m; either x0 == x1 or y0 == y1.
struct WallSegment {
  float x0 = 0.0F;
  float y0 = 0.0F;
  float x1 = 0.0F;
  float y1 = 0.0F;
};

/// Every cell edge whose two sides differ in blocking, merged into maximal runs along each grid
/// line. Which side blocks does not matter to a ray, so runs continue across such changes.
/// Built in parallel in the caller's task arena; the list and its order do not depend on the
/// thread count.
[[nodiscard]] std::vector<WallSegment> wall_segments(const CellMask& mask);

}  // namespace mote::detail
