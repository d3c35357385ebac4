#pragma once
// The quantity augmented MCL tracks (Thrun et al., table 8.3, lines 10-13): how well the map
// explains the scan at the particles, measured so that its drop means the same thing whatever
// the sensor model, the beam count, the likelihood combination and the tempering. Internal.

#include <cstddef>
#include <vector>

#include "mote/engine/beams.hpp"
#include "mote/engine/particles.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// The share of a scan's beam endpoints that land within `tolerance` of a mapped obstacle,
/// averaged over the particles by their normalized weights: about 0.8-1 while the filter
/// tracks, the share a random pose gets (0.1-0.4 in the logs we have) once it is lost. Thrun's
/// w_avg, the mean likelihood itself, scales with e^(beams) and with the tempering exponent,
/// so its w_fast / w_slow ratio signals a failure only for one beam count and model; a share
/// of beams has no such scale.
class ScanFit {
 public:
  /// Particles evaluated at most: an even stride over the set (deterministic).
  static constexpr std::size_t kSample = 256;

  /// Distances from the grid's occupied cells, clamped just above the tolerance.
  ScanFit(const OccupancyGrid& grid, double tolerance_m);

  /// The weighted share in [0, 1], or 0 when no beam has an endpoint (all max range).
  [[nodiscard]] double operator()(const BeamSet& beams, const ConstParticleView& particles) const;

 private:
  // Share of the robot-frame endpoints `ends` near an obstacle seen from `pose`.
  [[nodiscard]] double explained_share(const std::vector<Point2>& ends, const Pose2& pose) const;

  OccupancyGrid grid_;
  DistanceField field_;
  float tolerance_;
};

}  // namespace mote
