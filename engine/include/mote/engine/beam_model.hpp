#pragma once
/// \file
/// The beam model (Thrun et al., table 6.1): every selected beam is compared with the range an
/// Embree ray cast from the particle's sensor pose expects.

#include <cstddef>

#include "mote/engine/beams.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/sensor_model.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote {

/// Beam model parameters: the mixture (amcl names) and the likelihood exponent.
struct BeamModelParams {
  MixtureParams mixture;
  double tempering = 1.0;      ///< tau: log-likelihoods are multiplied by it
  bool unknown_blocks = true;  ///< unknown cells stop rays (amcl's map_calc_range)
};

/// Weighs particles by sum over beams of log p(z_b | z*_b(x)) (eqs. 6.4-6.11), z* ray-cast with
/// Embree in 16-ray packets. Max-range readings count through the z_max point mass.
class BeamModel {
 public:
  /// Builds the Embree scene of the grid.
  BeamModel(const OccupancyGrid& grid, const BeamModelParams& params);

  /// Adds tau * log p(z | x_i) to particles.logw[i] for i in [begin, end). Reentrant.
  void weigh(const BeamSet& beams, const ParticleView& particles, std::size_t begin,
             std::size_t end) const;

  [[nodiscard]] const BeamModelParams& params() const noexcept { return params_; }
  [[nodiscard]] const RayCaster& caster() const noexcept { return caster_; }

 private:
  BeamModelParams params_;
  RayCaster caster_;
};

static_assert(SensorModel<BeamModel>);

}  // namespace mote
