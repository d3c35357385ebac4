#pragma once
// The map as the per-update checks read it: the grid, its distance field and the sensor
// mixture, shared by the unmapped-obstacle filter (blocked_beams.hpp), the scan matcher
// (scan_match.hpp) and the see-through test (see_through.hpp). Internal.

#include "mote/engine/sensor_model.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/maps/signed_distance_field.hpp"

namespace mote {

struct MapField {
  /// The signed field clamped at max_distance; its obstacle_distance() is the distance from the
  /// grid's occupied cells (unknown cells are not obstacles, as in amcl's likelihood field), so
  /// one transform serves the scan matcher and the ray walks. Build it inside the Localizer's
  /// task arena: the transforms run on the calling arena's threads.
  MapField(const OccupancyGrid& map, const MixtureParams& sensor, double max_distance)
      : grid(map), signed_field(map, static_cast<float>(max_distance)), mixture(sensor) {}

  const OccupancyGrid& grid;         // the Localizer's map
  SignedDistanceField signed_field;  // the scan matcher's, and the walks' obstacle distance
  MixtureParams mixture;
};

}  // namespace mote
