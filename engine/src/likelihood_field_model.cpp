#include "mote/engine/likelihood_field_model.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "likelihood_gather.hpp"
#include "mote/core/error.hpp"

namespace mote {

namespace {

// Particles handled together: their accumulators and sin/cos stay in L1 while every beam
// streams over them (the loop over particles is the vectorized one).
constexpr std::size_t kBlock = detail::kLikelihoodBlock;

float checked_clamp(const LikelihoodFieldParams& p) {
  if (!(p.max_distance > 0.0)) {
    throw ConfigError("likelihood field: max_distance must be positive");
  }
  return static_cast<float>(p.max_distance);
}

// The grid with only the surface of each obstacle kept occupied: occupied cells with a free
// 4-neighbour. A beam ends on a surface; measured to every occupied cell, an endpoint that
// overshoots into a thick wall would cost nothing (its distance stays 0), which biases the
// field's maximum towards poses that see into walls. Measured to surfaces, overshooting costs
// as much as falling short. (ObstacleCells::kSurface is the same rule without the copy.)
OccupancyGrid surface_of(const OccupancyGrid& grid) {
  std::vector<CellState> cells(grid.cells().size(), CellState::kFree);
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      if (grid.at({i, j}) != CellState::kOccupied) continue;
      const bool surface = grid.at_or({i - 1, j}, CellState::kOccupied) == CellState::kFree ||
                           grid.at_or({i + 1, j}, CellState::kOccupied) == CellState::kFree ||
                           grid.at_or({i, j - 1}, CellState::kOccupied) == CellState::kFree ||
                           grid.at_or({i, j + 1}, CellState::kOccupied) == CellState::kFree;
      if (surface) cells[grid.linear_index({i, j})] = CellState::kOccupied;
    }
  }
  return {grid.width(), grid.height(), grid.resolution(), grid.origin(), std::move(cells)};
}

}  // namespace

LikelihoodFieldModel::LikelihoodFieldModel(const OccupancyGrid& grid,
                                           const LikelihoodFieldParams& params)
    : params_(params), resolution_(grid.resolution()) {
  const float clamp = checked_clamp(params);
  if (SquaredDistances::saturation(resolution_, clamp, SquaredDistances::kMaxSaturation) > 0) {
    squared_.emplace(grid, ObstacleCells::kSurface, clamp);
  } else {
    field_.emplace(surface_of(grid),
                   DistanceFieldOptions{.unknown_is_obstacle = false, .max_distance = clamp});
  }
}

LikelihoodFieldModel::LikelihoodFieldModel(std::shared_ptr<const OccupancyGrid> grid,
                                           const LikelihoodFieldParams& params)
    : params_(params), resolution_(grid ? grid->resolution() : 1.0) {
  if (!grid) throw ConfigError("likelihood field: the grid is null");
  const float clamp = checked_clamp(params);
  if (SquaredDistances::saturation(resolution_, clamp, SquaredDistances::kMaxSaturation) > 0) {
    grid_ = std::move(grid);
  } else {
    field_.emplace(surface_of(*grid),
                   DistanceFieldOptions{.unknown_is_obstacle = false, .max_distance = clamp});
  }
}

void LikelihoodFieldModel::prepare(const BeamSet& beams) {
  if (table_ && beams.range_max == table_range_max_) return;
  const double range_max = beams.range_max;
  const MixtureParams& m = params_.mixture;
  const double max_d = params_.max_distance;
  // The distance field measures to occupied cell centres, but a beam ends on a cell's face,
  // half a cell nearer: without this correction the field's maximum sits up to half a cell
  // (2.5 cm on a 5 cm map) off the true pose, in the direction of the walls in view.
  const double half_cell = 0.5 * resolution_;
  auto value = [&](float d) -> float {
    // amcl clamps at max_occ_dist.
    const double dist = std::min(std::max(0.0, static_cast<double>(d) - half_cell), max_d);
    if (params_.combination == LikelihoodCombination::kAmclCubedSum) {
      const double pz = amcl_likelihood_field_pz(dist, range_max, m);
      return static_cast<float>(pz * pz * pz);
    }
    return static_cast<float>(std::log(likelihood_field_density(dist, range_max, m)));
  };
  const float outside = value(static_cast<float>(max_d + half_cell));
  table_.reset();  // the old table goes before the new one is built: one table at a time
  if (grid_) {
    table_ = std::make_unique<LikelihoodTable>(*grid_, ObstacleCells::kSurface,
                                               static_cast<float>(max_d), value, outside);
  } else if (squared_) {
    table_ = std::make_unique<LikelihoodTable>(*squared_, value, outside);
  } else {
    table_ = std::make_unique<LikelihoodTable>(*field_, value, outside);
  }
  table_range_max_ = beams.range_max;
}

void LikelihoodFieldModel::weigh(const BeamSet& beams, const ParticleView& particles,
                                 std::size_t begin, std::size_t end) const {
  if (!table_ || beams.range_max != table_range_max_) {
    throw Error("LikelihoodFieldModel::weigh: call prepare() with this scan first");
  }
  // Beam endpoints in the robot frame: sensor pose composed with (r cos a, r sin a).
  const std::size_t n = beams.size();
  std::vector<float> ex(n);
  std::vector<float> ey(n);
  const Pose2& s = beams.sensor_pose;
  for (std::size_t b = 0; b < n; ++b) {
    const double a = s.theta + beams.angle[b];
    ex[b] = static_cast<float>(s.x + beams.range[b] * std::cos(a));
    ey[b] = static_cast<float>(s.y + beams.range[b] * std::sin(a));
  }
  for (std::size_t block = begin; block < end; block += kBlock) {
    weigh_block(ex.data(), ey.data(), n, particles, block, std::min(end, block + kBlock));
  }
}

void LikelihoodFieldModel::weigh_block(const float* endpoint_x, const float* endpoint_y,
                                       std::size_t beams, const ParticleView& particles,
                                       std::size_t begin, std::size_t end) const {
  const std::size_t count = end - begin;
  // Padding lanes past the last particle are computed and dropped (particles.hpp allows it),
  // so every particle takes the vector path when chunks start at multiples of the padding.
  const std::size_t lanes = std::min(pad_particles(count), particles.padded_size() - begin);
  alignas(64) float sum[kBlock];
  detail::likelihood_block_sums(table_->view(), particles, begin, lanes,
                                {endpoint_x, endpoint_y, beams}, sum);
  const auto tau = static_cast<float>(params_.tempering);
  const bool cubed = params_.combination == LikelihoodCombination::kAmclCubedSum;
  for (std::size_t k = 0; k < count; ++k) {
    const float log_likelihood = cubed ? std::log1p(sum[k]) : sum[k];
    particles.logw[begin + k] += tau * log_likelihood;
  }
}

}  // namespace mote
