#include "mote/engine/beam_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace mote {

int max_table_lattice(double sigma_hit, double resolution) {
  // The table answers a sensor with the ray of the lattice point, of the 3 x 3 around it, whose
  // ray passes closest: at most half the spacing from the sensor along either axis, so at most
  // spacing / sqrt(2) across the ray (the offset along it is corrected). Within sigma_hit:
  // spacing <= sqrt(2) sigma_hit. (The epsilon keeps exact quotients whole.)
  const double cells = std::numbers::sqrt2 * sigma_hit / resolution + 1e-9;
  if (!(cells >= 1.0)) return 1;  // also NaN: a table on every cell or none
  return static_cast<int>(std::min(cells, 1e6));
}

BeamModel::BeamModel(const OccupancyGrid& grid, const BeamModelParams& params,
                     const std::optional<RangeTableOptions>& table)
    : params_(params) {
  if (table) {
    RangeTableOptions options = *table;
    options.unknown_blocks = params.unknown_blocks;
    casting_.table_asked = true;
    casting_.max_lattice = max_table_lattice(params.mixture.sigma_hit, grid.resolution());
    casting_.budget_lattice = range_table_lattice(grid, options);
    casting_.table = casting_.budget_lattice > 0 && casting_.budget_lattice <= casting_.max_lattice;
    if (casting_.table) {
      table_.emplace(grid, options);
      return;
    }
  }
  exact_.emplace(grid, RayCastOptions{.unknown_blocks = params.unknown_blocks});
}

void BeamModel::expected_ranges(const RayBatch& batch, std::span<float> ranges) const {
  if (table_) {
    table_->cast(batch, ranges);
  } else {
    exact_->cast(batch, ranges);
  }
}

void BeamModel::weigh(const BeamSet& beams, const ParticleView& particles, std::size_t begin,
                      std::size_t end) const {
  const std::size_t count = end - begin;
  const std::size_t n_beams = beams.size();
  if (count == 0 || n_beams == 0) return;
  // A buffer per call, not per thread: the cast below is itself parallel, and a thread waiting
  // on it may steal another chunk of this same loop and re-enter weigh().
  std::vector<float> expected(count * n_beams);
  const RayBatch batch{.x = {particles.x + begin, count},
                       .y = {particles.y + begin, count},
                       .theta = {particles.theta + begin, count},
                       .beam_angles = beams.angle,
                       .sensor_offset = beams.sensor_pose,
                       .max_range = beams.range_max};
  expected_ranges(batch, expected);

  add_beam_log_likelihoods(beams.range, beams.range_max, expected, params_,
                           {particles.logw + begin, count});
}

}  // namespace mote
