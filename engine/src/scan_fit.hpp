#pragma once
// The quantity augmented MCL tracks (Thrun et al., table 8.3, lines 10-13): how well the map
// explains the scan at the particles, measured so that its drop means the same thing whatever
// the sensor model, the beam count, the likelihood combination and the tempering. Internal.

#include <cstddef>
#include <vector>

#include "mote/engine/beams.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/sensor_model.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// The per-beam geometric mean of the likelihood-field density (Thrun table 6.3, line 8:
/// z_hit N(d; 0, sigma_hit^2) + z_rand / z_max, d the endpoint's distance to the nearest
/// obstacle), averaged over the particles by their normalized weights. The scan likelihood
/// itself, Thrun's w_avg, scales with e^(beams), with the tempering exponent and with the
/// model (amcl's 1 + sum pz^3 spans 0-2.2 nats for 60 beams), so its w_fast / w_slow ratio
/// signals a failure only for one beam count and model; a per-beam mean of one fixed density
/// has no such scale. It is evaluated for the beam model too, from the same map.
class ScanFit {
 public:
  /// Particles evaluated at most: an even stride over the set (deterministic).
  static constexpr std::size_t kSample = 256;

  /// Distances from the grid's occupied cells, clamped at max_distance (amcl's
  /// laser_likelihood_max_dist).
  ScanFit(const OccupancyGrid& grid, const MixtureParams& mixture, double max_distance);

  /// The weighted geometric-mean beam likelihood (> 0), or 0 when no beam has an endpoint
  /// (every reading at max range) or no particle has weight.
  /// Rebuilds its per-cell table when the scan's range_max changes (z_rand / z_max), so call
  /// it from one thread.
  [[nodiscard]] double operator()(const BeamSet& beams, const ConstParticleView& particles);

  [[nodiscard]] const OccupancyGrid& grid() const noexcept { return grid_; }
  [[nodiscard]] const MixtureParams& mixture() const noexcept { return mixture_; }
  /// Distances to the nearest occupied cell, m, clamped at max_distance.
  [[nodiscard]] const DistanceField& field() const noexcept { return field_; }

 private:
  // Mean log density of the robot-frame endpoints `ends` seen from `pose`.
  [[nodiscard]] double mean_log_density(const std::vector<Point2>& ends, const Pose2& pose) const;
  // The log density of every cell's distance for this range_max, and of an off-map endpoint.
  void build_table(float range_max);

  OccupancyGrid grid_;
  DistanceField field_;
  MixtureParams mixture_;
  float max_distance_;
  std::vector<float> log_density_;
  float off_map_ = 0.0F;
  float table_range_max_ = -1.0F;
};

}  // namespace mote
