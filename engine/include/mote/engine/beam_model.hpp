#pragma once
/// \file
/// The beam model (Thrun et al., table 6.1): every selected beam is compared with the range an
/// Embree ray cast from the particle's sensor pose expects, or (ray_casting: table) the range a
/// precomputed RangeTable holds for that pose.

#include <cstddef>
#include <optional>
#include <span>

#include "mote/engine/beams.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/sensor_model.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/raycast/range_table.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote {

/// Beam model parameters: the mixture (amcl names) and the likelihood exponent.
struct BeamModelParams {
  MixtureParams mixture;
  double tempering = 1.0;      ///< tau: log-likelihoods are multiplied by it
  bool unknown_blocks = true;  ///< unknown cells stop rays (amcl's map_calc_range)
  /// kProduct: sum of log p (table 6.1); kAmclCubedSum: log(1 + sum pz^3) with amcl's terms
  /// (amcl_beam_pz), for nav2_amcl's defaults.
  LikelihoodCombination combination = LikelihoodCombination::kProduct;
};

/// How the beam model finds its expected ranges, and why.
struct BeamCasting {
  bool table_asked = false;  ///< RangeTableOptions were given (ray_casting: table)
  bool table = false;        ///< a RangeTable serves the casts; otherwise exact Embree casting
  /// The lattice (cells) the table's budget gives on this map; 0 when no lattice fits.
  int budget_lattice = 0;
  /// The coarsest lattice whose rays pass within sigma_hit of the sensor, the noise the model
  /// already assumes of every expected range: the ray read lies at most spacing / sqrt(2) to its
  /// side, so floor(sqrt(2) sigma_hit / resolution), at least 1.
  int max_lattice = 0;
};

/// BeamCasting::max_lattice for a sigma_hit (m) and a map resolution (m per cell).
[[nodiscard]] int max_table_lattice(double sigma_hit, double resolution);

/// Weighs particles by sum over beams of log p(z_b | z*_b(x)) (eqs. 6.4-6.11), z* ray-cast with
/// Embree in 16-ray packets. A max-range reading is weighed at z = z_max by the whole mixture
/// (eq. 6.12: the z_max point mass plus p_hit and p_short there), so particles that expect a
/// wall short of z_max are penalized for it.
class BeamModel {
 public:
  /// Builds the Embree scene of the grid, or, when `table` is set, a RangeTable with those
  /// options (their unknown_blocks replaced by params.unknown_blocks) if its budget holds it on
  /// a lattice whose rays pass within sigma_hit of the sensor (BeamCasting::max_lattice). A
  /// coarser lattice reads rays farther to the sensor's side than the noise the model allows
  /// every expected range, and the lattice grows with the map's area (a 490 m floor at 256 MB:
  /// 19 cells), so there the model casts exactly: the accuracy does not depend on the size of
  /// the building. casting() says which and why.
  BeamModel(const OccupancyGrid& grid, const BeamModelParams& params,
            const std::optional<RangeTableOptions>& table = std::nullopt);

  /// Adds tau * log p(z | x_i) to particles.logw[i] for i in [begin, end). Reentrant.
  void weigh(const BeamSet& beams, const ParticleView& particles, std::size_t begin,
             std::size_t end) const;

  [[nodiscard]] const BeamModelParams& params() const noexcept { return params_; }
  /// Fills the expected ranges of a batch from whichever source the params chose.
  void expected_ranges(const RayBatch& batch, std::span<float> ranges) const;
  /// The range table, or nullptr under exact casting.
  [[nodiscard]] const RangeTable* range_table() const noexcept {
    return table_ ? &*table_ : nullptr;
  }
  [[nodiscard]] const BeamCasting& casting() const noexcept { return casting_; }

 private:
  BeamModelParams params_;
  std::optional<RayCaster> exact_;
  std::optional<RangeTable> table_;
  BeamCasting casting_;
};

static_assert(SensorModel<BeamModel>);

/// The beam model's scan log-likelihood once the expected ranges are cast: adds
/// tempering * sum_b log p(ranges[b] | expected[i * B + b]) (Thrun table 6.1) to logw[i] for
/// every particle i, with B = ranges.size() and expected particle-major as RayCaster::cast fills
/// it. Computes what summing beam_log_likelihood does, in float and vectorized over particles:
/// each beam's term is within 1e-6 * (1 + |term|) of the double formula. Expected ranges outside
/// [0, range_max] (NaN for a particle with a non-finite pose, whose logw becomes NaN) and mixtures
/// outside float's comfortable range (z_rand near 0) take the double formula itself. Throws
/// ConfigError when expected.size() != logw.size() * ranges.size().
void add_beam_log_likelihoods(std::span<const float> ranges, float range_max,
                              std::span<const float> expected, const BeamModelParams& params,
                              std::span<float> logw);

}  // namespace mote
