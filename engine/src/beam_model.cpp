#include "mote/engine/beam_model.hpp"

#include <vector>

namespace mote {

BeamModel::BeamModel(const OccupancyGrid& grid, const BeamModelParams& params,
                     const std::optional<RangeTableOptions>& table)
    : params_(params) {
  if (table) {
    RangeTableOptions options = *table;
    options.unknown_blocks = params.unknown_blocks;
    table_.emplace(grid, options);
  } else {
    exact_.emplace(grid, RayCastOptions{.unknown_blocks = params.unknown_blocks});
  }
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
