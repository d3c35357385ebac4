#pragma once
// The localization state's evidence against a pose: readings that would have had to pass
// through a mapped obstacle to end where they did. Internal.

#include "field_walker.hpp"
#include "mote/core/pose.hpp"
#include "mote/engine/beams.hpp"

namespace mote {

/// Share of the beams with an endpoint whose ray, from the sensor at robot pose `pose`, meets
/// a mapped obstacle more than `margin` (m) before its endpoint. At the true pose only a
/// random reading (Thrun et al., eq. 6.11), the far tail of the hit Gaussian (eq. 6.4) or an
/// error of the map (glass, an open door drawn closed) can do that; at a wrong pose a
/// reading crosses a wall whenever the belief puts one between the robot and the endpoint.
/// NaN when no beam has an endpoint (every weighed beam a no-return): nothing to judge by, and
/// the localization state then stays as it was.
[[nodiscard]] double see_through_share(const BeamSet& beams, const Pose2& pose,
                                       const FieldWalker& walk, double margin);

}  // namespace mote
