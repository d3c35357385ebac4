// BeamModel::weigh: the Embree ranges of particles [begin, end) and the batched likelihood,
// against casting the same rays and summing the scalar double beam_log_likelihood.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "mote/engine/beam_model.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {
namespace {

// A 10 m x 8 m room of 10 cm cells with walls on its border and a pillar in it.
OccupancyGrid room() {
  const int width = 100;
  const int height = 80;
  std::vector<CellState> cells(static_cast<std::size_t>(width * height), CellState::kFree);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const bool wall = i == 0 || j == 0 || i == width - 1 || j == height - 1;
      const bool pillar = i >= 40 && i < 46 && j >= 30 && j < 36;
      if (wall || pillar) cells[static_cast<std::size_t>(j * width + i)] = CellState::kOccupied;
    }
  }
  return {width, height, 0.1, {0.0, 0.0, 0.0}, std::move(cells)};
}

TEST(BeamModelWeigh, AddsTheScalarScanLikelihoodOfTheCastRangesToItsRange) {
  const OccupancyGrid grid = room();
  const BeamModel model(grid, {.mixture = {}, .tempering = 0.5});
  BeamSet beams;
  beams.range_max = 12.0F;
  beams.sensor_pose = {0.2, 0.0, 0.0};
  for (int b = 0; b < 60; ++b) {
    beams.angle.push_back(static_cast<float>(std::numbers::pi * (b / 59.0 - 0.5)));
    beams.range.push_back(b % 13 == 0 ? beams.range_max : 0.5F + 0.1F * static_cast<float>(b));
  }
  ParticleStore store(300);
  const ParticleView particles = store.view();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0F, 1.0F);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    // Some particles stand inside the pillar or the walls (z* = 0 for every beam).
    particles.set_pose(i, {10.0 * u(rng), 8.0 * u(rng), 6.0 * u(rng)});
    particles.logw[i] = -1.0F;
  }
  particles.x[100] =
      std::numeric_limits<float>::quiet_NaN();  // a non-finite pose: NaN expected ranges
  const std::size_t begin = 16;
  const std::size_t end = 290;
  model.weigh(beams, particles, begin, end);

  std::vector<float> expected((end - begin) * beams.size());
  model.expected_ranges({.x = {particles.x + begin, end - begin},
                         .y = {particles.y + begin, end - begin},
                         .theta = {particles.theta + begin, end - begin},
                         .beam_angles = beams.angle,
                         .sensor_offset = beams.sensor_pose,
                         .max_range = beams.range_max},
                        expected);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    SCOPED_TRACE(testing::Message() << "particle " << i);
    if (i < begin || i >= end) {
      EXPECT_EQ(particles.logw[i], -1.0F) << "outside [begin, end)";
      continue;
    }
    double sum = 0.0;
    double scale = 0.0;
    for (std::size_t b = 0; b < beams.size(); ++b) {
      const float z_star = expected[(i - begin) * beams.size() + b];
      const double term =
          beam_log_likelihood(beams.range[b], z_star, beams.range_max, model.params().mixture);
      sum += term;
      scale += 1.0 + std::abs(term);
    }
    // test_beam_likelihood.cpp's bound times tau, plus float's rounding of logw.
    const double exact = -1.0 + 0.5 * sum;
    if (std::isnan(exact)) {
      EXPECT_TRUE(std::isnan(particles.logw[i]));
    } else {
      EXPECT_NEAR(particles.logw[i], exact, 0.5 * 1e-6 * scale + 6e-8 * std::abs(exact));
    }
  }
  EXPECT_TRUE(std::isnan(particles.logw[100]));
}

// The range table serves the casts only on a lattice no coarser than sqrt(2) sigma_hit; where the
// budget allows only a coarser one (a big map), or none at all, the model casts exactly.
TEST(BeamModelCasting, TheTableOnlyOnALatticeWithinSigmaHitElseExactCasting) {
  const OccupancyGrid grid = room();  // 10 cm cells: sigma_hit 0.2 m allows a lattice of 2
  const auto model_with = [&](double budget_mb, double sigma_hit) {
    MixtureParams mixture;
    mixture.sigma_hit = sigma_hit;
    return BeamModel(
        grid, {.mixture = mixture},
        RangeTableOptions{.memory_budget_bytes = static_cast<std::size_t>(budget_mb * 1048576.0)});
  };
  const BeamModel every_cell = model_with(64.0, 0.2);
  EXPECT_TRUE(every_cell.casting().table);
  EXPECT_EQ(every_cell.casting().budget_lattice, 1);
  ASSERT_NE(every_cell.range_table(), nullptr);
  EXPECT_EQ(every_cell.range_table()->stats().lattice, 1);

  const BeamModel coarse = model_with(1.0, 0.2);  // 7.7 MB on every cell
  EXPECT_TRUE(coarse.casting().table_asked);
  EXPECT_EQ(coarse.casting().max_lattice, 2);
  EXPECT_GT(coarse.casting().budget_lattice, 2);
  EXPECT_FALSE(coarse.casting().table);
  EXPECT_EQ(coarse.range_table(), nullptr);

  const BeamModel wide_noise = model_with(1.0, 0.5);
  EXPECT_EQ(wide_noise.casting().max_lattice, 7);  // floor(sqrt(2) 0.5 / 0.1)
  ASSERT_NE(wide_noise.range_table(), nullptr);
  EXPECT_EQ(wide_noise.range_table()->stats().lattice, coarse.casting().budget_lattice);

  // The bound itself: floor(sqrt(2) sigma_hit / resolution), at least 1 for any input.
  EXPECT_EQ(max_table_lattice(0.2, 0.05), 5);
  EXPECT_EQ(max_table_lattice(0.2, 0.03), 9);
  EXPECT_EQ(max_table_lattice(0.01, 0.05), 1);
  EXPECT_EQ(max_table_lattice(std::numeric_limits<double>::quiet_NaN(), 0.05), 1);
  EXPECT_EQ(max_table_lattice(1e300, 0.05), 1000000);

  const BeamModel none = model_with(0.001, 0.2);  // no lattice fits: exact casting, no error
  EXPECT_EQ(none.casting().budget_lattice, 0);
  EXPECT_FALSE(none.casting().table);

  // Without the table the ranges are exact casting's.
  const BeamModel exact(grid, {});
  EXPECT_FALSE(exact.casting().table_asked);
  const std::vector<float> angles{0.0F, 1.0F, 2.0F, -2.5F};
  const std::vector<float> x{2.05F, 7.3F};
  const std::vector<float> y{1.5F, 6.1F};
  const std::vector<float> theta{0.3F, -1.2F};
  const RayBatch batch{.x = x,
                       .y = y,
                       .theta = theta,
                       .beam_angles = angles,
                       .sensor_offset = {},
                       .max_range = 12.0F};
  std::vector<float> from_exact(8);
  std::vector<float> from_coarse(8);
  exact.expected_ranges(batch, from_exact);
  coarse.expected_ranges(batch, from_coarse);
  EXPECT_EQ(from_coarse, from_exact);
}

}  // namespace
}  // namespace mote
