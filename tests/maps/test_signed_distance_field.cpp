// The signed distance field: zero on the surface between an occupied cell and its neighbour,
// negative inside a wall however thick it is drawn, positive outside, against a brute force.
#include "mote/maps/signed_distance_field.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "mote/core/error.hpp"

namespace mote {
namespace {

constexpr double kRes = 0.05;

// A 20 x 9 grid, free, with a vertical wall of `thickness` cells at columns [8, 8 + thickness)
// and an unknown strip at column 18.
OccupancyGrid wall_grid(int thickness) {
  const int w = 20;
  const int h = 9;
  std::vector<CellState> cells(static_cast<std::size_t>(w * h), CellState::kFree);
  for (int j = 0; j < h; ++j) {
    for (int i = 8; i < 8 + thickness; ++i)
      cells[static_cast<std::size_t>(j * w + i)] = CellState::kOccupied;
    cells[static_cast<std::size_t>(j * w + 18)] = CellState::kUnknown;
  }
  return {w, h, kRes, Pose2{}, std::move(cells)};
}

TEST(SignedDistanceField, IsZeroOnTheSurfaceOfAThickWallAndNegativeInside) {
  const SignedDistanceField f(wall_grid(5), 2.0F);
  // Outside: centres 1, 2 cells from the wall's first column, half a cell less from its face.
  EXPECT_NEAR(f.at(7, 4), 0.5 * kRes, 1e-6);
  EXPECT_NEAR(f.at(6, 4), 1.5 * kRes, 1e-6);
  // Inside: the face cell half a cell deep, the middle of the wall 2.5 cells deep.
  EXPECT_NEAR(f.at(8, 4), -0.5 * kRes, 1e-6);
  EXPECT_NEAR(f.at(10, 4), -2.5 * kRes, 1e-6);
  EXPECT_NEAR(f.at(12, 4), -0.5 * kRes, 1e-6);
  // Unknown cells are not obstacles: positive, measured to the wall.
  EXPECT_NEAR(f.at(18, 4), (18 - 12) * kRes - 0.5 * kRes, 1e-6);
  // Half-way between centres across the face, the interpolant is zero: (0.5 + -0.5) / 2.
  EXPECT_NEAR(0.5 * (f.at(7, 4) + f.at(8, 4)), 0.0, 1e-6);
}

TEST(SignedDistanceField, MatchesABruteForceOnRandomGrids) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int w = 23;
  const int h = 17;
  std::vector<CellState> cells(static_cast<std::size_t>(w * h));
  for (CellState& c : cells) {
    const double r = u(rng);
    c = r < 0.3 ? CellState::kOccupied : (r < 0.4 ? CellState::kUnknown : CellState::kFree);
  }
  const OccupancyGrid grid(w, h, kRes, Pose2{0.5, -1.0, 0.2}, cells);
  const float max_distance = 0.4F;
  const SignedDistanceField f(grid, max_distance);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const bool inside = grid.at({i, j}) == CellState::kOccupied;
      double nearest = std::numeric_limits<double>::infinity();
      for (int b = 0; b < h; ++b) {
        for (int a = 0; a < w; ++a) {
          // Outside: the nearest occupied cell; inside: the nearest cell that is not.
          if ((grid.at({a, b}) == CellState::kOccupied) == inside) continue;
          nearest = std::min(nearest, std::hypot(a - i, b - j) * kRes);
        }
      }
      const double expected = std::min(nearest - 0.5 * kRes, static_cast<double>(max_distance));
      ASSERT_NEAR(f.at(i, j), inside ? -expected : expected, 1e-5) << i << ", " << j;
    }
  }
}

TEST(SignedDistanceField, RefusesANonPositiveClamp) {
  EXPECT_THROW(SignedDistanceField(wall_grid(1), 0.0F), ConfigError);
}

}  // namespace
}  // namespace mote
