#pragma once
/// \file
/// The likelihood-field model (Thrun et al., table 6.3): each beam endpoint, projected from the
/// particle's pose, reads a precomputed table over the map's distance field; one sin/cos per
/// particle, one lookup per beam.

#include <cstddef>
#include <memory>
#include <optional>

#include "mote/engine/beams.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/sensor_model.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/likelihood_table.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/maps/squared_distances.hpp"

namespace mote {

/// Likelihood-field parameters (amcl names where they exist).
struct LikelihoodFieldParams {
  MixtureParams mixture;      ///< z_hit, z_rand, sigma_hit are used
  double max_distance = 2.0;  ///< m: laser_likelihood_max_dist, the distance field's clamp
  LikelihoodCombination combination = LikelihoodCombination::kProduct;
  double tempering = 1.0;  ///< tau: log-likelihoods are multiplied by it
};

/// Weighs particles by the likelihood field. In kProduct mode the table holds
/// log(z_hit N(d; 0, sigma_hit^2) + z_rand / z_max) and a particle's log-likelihood is the sum
/// over beams (the textbook product, never exponentiated, so it cannot underflow). In
/// kAmclCubedSum mode the table holds pz^3 with amcl's unnormalized pz and the log-likelihood is
/// log(1 + sum pz^3). Endpoints off the map read the value at max_distance, as in amcl.
class LikelihoodFieldModel {
 public:
  /// Computes the distance field of the grid's obstacle surfaces (clamped at max_distance): 2
  /// bytes per cell up to 255 cells of max_distance, 4 beyond.
  LikelihoodFieldModel(const OccupancyGrid& grid, const LikelihoodFieldParams& params);
  /// The same, sharing the grid instead: nothing is built here, and prepare() builds the table
  /// straight from the grid (4 bytes per cell, no distance field kept; a new range_max builds
  /// it again). Clamps past 255 cells keep the float field as above. Throws ConfigError on a
  /// null grid.
  LikelihoodFieldModel(std::shared_ptr<const OccupancyGrid> grid,
                       const LikelihoodFieldParams& params);

  /// Builds the table for the scan's range_max (z_rand / z_max depends on it); a no-op when it
  /// is unchanged. Call before weigh() from one thread.
  void prepare(const BeamSet& beams);

  /// Adds tau * log p(z | x_i) to particles.logw[i] for i in [begin, end). Reentrant.
  void weigh(const BeamSet& beams, const ParticleView& particles, std::size_t begin,
             std::size_t end) const;

  [[nodiscard]] const LikelihoodFieldParams& params() const noexcept { return params_; }
  /// The current table (null before the first prepare()).
  [[nodiscard]] const LikelihoodTable* table() const noexcept { return table_.get(); }

 private:
  void weigh_block(const float* endpoint_x, const float* endpoint_y, std::size_t beams,
                   const ParticleView& particles, std::size_t begin, std::size_t end) const;

  LikelihoodFieldParams params_;
  double resolution_;                          // m per cell
  std::optional<SquaredDistances> squared_;    // the compact field, when the clamp fits
  std::optional<DistanceField> field_;         // otherwise
  std::shared_ptr<const OccupancyGrid> grid_;  // the shared grid, when neither is kept
  std::unique_ptr<LikelihoodTable> table_;
  float table_range_max_ = 0.0F;
};

static_assert(SensorModel<LikelihoodFieldModel>);

}  // namespace mote
