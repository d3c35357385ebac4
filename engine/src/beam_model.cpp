#include "mote/engine/beam_model.hpp"

#include <vector>

namespace mote {

BeamModel::BeamModel(const OccupancyGrid& grid, const BeamModelParams& params)
    : params_(params), caster_(grid, RayCastOptions{.unknown_blocks = params.unknown_blocks}) {}

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
  caster_.cast(batch, expected);

  const double range_max = beams.range_max;
  for (std::size_t p = 0; p < count; ++p) {
    const float* z_star = expected.data() + p * n_beams;
    double log_likelihood = 0.0;
    for (std::size_t b = 0; b < n_beams; ++b) {
      log_likelihood += beam_log_likelihood(beams.range[b], z_star[b], range_max, params_.mixture);
    }
    particles.logw[begin + p] += static_cast<float>(params_.tempering * log_likelihood);
  }
}

}  // namespace mote
