// The compact transforms against the float ones they replace, bit for bit: the squared
// distances against DistanceField for every obstacle rule and clamp, the likelihood table built
// from them, and the signed field's codes against the two float transforms it used to keep.
#include "mote/maps/squared_distances.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/likelihood_table.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/maps/signed_distance_field.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

// Walls and unknown blobs at random, with some thick walls and an empty band of rows and columns.
OccupancyGrid random_grid(int w, int h, double resolution, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, 99);
  std::vector<CellState> cells(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const int r = pick(rng);
      CellState s = r < 3 ? CellState::kOccupied : r < 6 ? CellState::kUnknown : CellState::kFree;
      if (i >= w / 3 && i < w / 3 + 4 && j > h / 2) s = CellState::kOccupied;  // a thick wall
      if (j >= h / 4 && j < h / 4 + 3) s = CellState::kFree;                   // empty rows
      cells[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
            static_cast<std::size_t>(i)] = s;
    }
  }
  return {w, h, resolution, Pose2{1.0, -2.0, 0.3}, std::move(cells)};
}

// The likelihood field's obstacle rule, as a grid: occupied cells with a free 4-neighbour.
OccupancyGrid surface_grid(const OccupancyGrid& grid) {
  std::vector<CellState> cells(grid.cells().size(), CellState::kFree);
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      if (grid.at({i, j}) != CellState::kOccupied) continue;
      const auto free_at = [&](int a, int b) {
        return grid.at_or({a, b}, CellState::kOccupied) == CellState::kFree;
      };
      if (free_at(i - 1, j) || free_at(i + 1, j) || free_at(i, j - 1) || free_at(i, j + 1)) {
        cells[grid.linear_index({i, j})] = CellState::kOccupied;
      }
    }
  }
  return {grid.width(), grid.height(), grid.resolution(), grid.origin(), std::move(cells)};
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

// Every cell of the compact field gives the float field's value, bit for bit.
void expect_equal(const SquaredDistances& compact, const DistanceField& reference) {
  const std::vector<float>& d = reference.distances();
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < d.size(); ++k) {
    ASSERT_LE(compact.at(k), compact.cap());
    mismatches += same_bits(compact.distance(compact.at(k)), d[k]) ? 0U : 1U;
  }
  EXPECT_EQ(mismatches, 0U);
}

struct Case {
  double resolution;
  float clamp;
};

class SquaredDistancesMatch : public ::testing::TestWithParam<Case> {};

TEST_P(SquaredDistancesMatch, DistanceFieldForEveryRule) {
  const Case c = GetParam();
  const OccupancyGrid grid = random_grid(173, 121, c.resolution, 7);
  expect_equal(SquaredDistances(grid, ObstacleCells::kOccupied, c.clamp),
               DistanceField(grid, {.unknown_is_obstacle = false, .max_distance = c.clamp}));
  expect_equal(SquaredDistances(grid, ObstacleCells::kOccupiedOrUnknown, c.clamp),
               DistanceField(grid, {.unknown_is_obstacle = true, .max_distance = c.clamp}));
  expect_equal(SquaredDistances(grid, ObstacleCells::kSurface, c.clamp),
               DistanceField(surface_grid(grid), {.max_distance = c.clamp}));
}

TEST_P(SquaredDistancesMatch, LikelihoodTableOfEitherField) {
  const Case c = GetParam();
  const OccupancyGrid grid = random_grid(151, 97, c.resolution, 11);
  const std::function<float(float)> f = [](float d) { return std::log(0.1F + std::exp(-d * d)); };
  const LikelihoodTable compact(SquaredDistances(grid, ObstacleCells::kOccupied, c.clamp), f, -7.0F,
                                2);
  const LikelihoodTable reference(DistanceField(grid, {.max_distance = c.clamp}), f, -7.0F, 2);
  const LikelihoodTable direct(grid, ObstacleCells::kOccupied, c.clamp, f, -7.0F, 2);
  for (const LikelihoodTable* t : {&compact, &direct}) {
    ASSERT_EQ(t->width(), reference.width());
    ASSERT_EQ(t->height(), reference.height());
    const std::size_t n = t->stride() * static_cast<std::size_t>(t->height());
    EXPECT_EQ(std::memcmp(t->data(), reference.data(), n * sizeof(float)), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Clamps, SquaredDistancesMatch,
                         ::testing::Values(Case{0.05, 2.0F}, Case{0.05, 0.05F}, Case{0.1, 1.0F},
                                           Case{0.05, 0.3F}, Case{0.05, 6.3F}, Case{0.013, 0.5F},
                                           Case{0.05, 12.0F}));

TEST(SquaredDistances, SaturationReachesTheClampAndRefusesWhatDoesNotFit) {
  EXPECT_EQ(SquaredDistances::saturation(0.05, 2.0F, 255), 40);
  EXPECT_EQ(SquaredDistances::saturation(0.05, 2.025F, 255), 41);
  EXPECT_EQ(SquaredDistances::saturation(0.01, 3.0F, 255), 0);
  EXPECT_EQ(SquaredDistances::saturation(0.05, std::numeric_limits<float>::infinity(), 255), 0);
  const OccupancyGrid grid = random_grid(20, 20, 0.01, 3);
  EXPECT_THROW(SquaredDistances(grid, ObstacleCells::kOccupied, 3.0F), ConfigError);
  EXPECT_THROW(SquaredDistances(grid, ObstacleCells::kOccupied, 0.0F), ConfigError);
}

TEST(SquaredDistances, AGridWithoutObstaclesIsAtTheClampEverywhere) {
  const OccupancyGrid grid(9, 5, 0.05, Pose2{}, std::vector<CellState>(45, CellState::kFree));
  const SquaredDistances d(grid, ObstacleCells::kOccupied, 1.0F);
  for (std::size_t k = 0; k < 45; ++k) EXPECT_EQ(d.distance(d.at(k)), 1.0F);
}

// The signed field as it was built before it kept codes: two float transforms.
void expect_signed_field_of(const OccupancyGrid& grid, float max_distance) {
  const SignedDistanceField field(grid, max_distance);
  const auto half = static_cast<float>(0.5 * grid.resolution());
  std::vector<CellState> flipped = grid.cells();
  for (CellState& c : flipped) {
    if (c != CellState::kUnknown) {
      c = c == CellState::kOccupied ? CellState::kFree : CellState::kOccupied;
    }
  }
  const OccupancyGrid inverse(grid.width(), grid.height(), grid.resolution(), grid.origin(),
                              std::move(flipped));
  const DistanceField out(grid, {.max_distance = max_distance + half});
  const DistanceField in(inverse,
                         {.unknown_is_obstacle = true, .max_distance = max_distance + half});
  const DistanceField plain(grid, {.max_distance = max_distance});
  std::size_t mismatches = 0;
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      const std::size_t k = grid.linear_index({i, j});
      const float expected = grid.cells()[k] == CellState::kOccupied
                                 ? -std::min(in.distances()[k] - half, max_distance)
                                 : std::min(out.distances()[k] - half, max_distance);
      mismatches += same_bits(field.at(i, j), expected) ? 0U : 1U;
      mismatches += same_bits(field.obstacle_distance(k), plain.distances()[k]) ? 0U : 1U;
    }
  }
  EXPECT_EQ(mismatches, 0U);
}

TEST(SignedDistanceField, CodesGiveTheFloatTransformsValues) {
  expect_signed_field_of(random_grid(131, 89, 0.05, 5), 2.0F);  // codes (41 cells)
  expect_signed_field_of(random_grid(131, 89, 0.05, 5), 0.4F);  // codes (9 cells)
  expect_signed_field_of(random_grid(131, 89, 0.05, 5), 7.0F);  // codes by the envelope
  expect_signed_field_of(random_grid(131, 89, 0.01, 5), 2.0F);  // floats (201 cells)
}

TEST(SquaredDistances, RecordedMapGivesDistanceFieldsValues) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  expect_equal(SquaredDistances(grid, ObstacleCells::kSurface, 2.0F),
               DistanceField(surface_grid(grid), {.max_distance = 2.0F}));
  expect_signed_field_of(grid, 2.0F);
}

}  // namespace
}  // namespace mote
