#include "see_through.hpp"

#include <cmath>
#include <cstddef>
#include <limits>

namespace mote {

double see_through_share(const BeamSet& beams, const Pose2& pose, const FieldWalker& walk,
                         double margin) {
  const Pose2 sensor = compose(pose, beams.sensor_pose);
  const Point2 origin = walk.cell_point({sensor.x, sensor.y});
  const double k = walk.inv_cell();
  std::size_t endpoints = 0;
  std::size_t through = 0;
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const double r = beams.range[b];
    if (!(r < beams.range_max)) continue;  // a no-return has no endpoint
    ++endpoints;
    const double a = sensor.theta + beams.angle[b];
    const Point2 u = walk.cell_direction(std::cos(a), std::sin(a));
    // The walk starts `margin` out as it stops `margin` short: a sensor that the refined pose
    // puts a few centimetres into a wall's cells (a thick wall drawn a cell too wide, a pose
    // error within sigma_hit) would otherwise see every ray through that wall.
    if (walk.runs_into_wall(origin, u, margin * k, (r - margin) * k)) ++through;
  }
  return endpoints > 0 ? static_cast<double>(through) / static_cast<double>(endpoints)
                       : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace mote
