// Exact ranges on hand-built grids, run against both casters through the shared interface.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "grids.hpp"
#include "mote/raycast/grid_ray_caster.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote {
namespace {

using std::numbers::pi;

// Float ray coordinates: ranges are exact up to float rounding of metre-scale values.
constexpr float kTol = 1e-5F;

template <class Caster>
class SyntheticRanges : public ::testing::Test {};
using Casters = ::testing::Types<RayCaster, GridRayCaster>;
TYPED_TEST_SUITE(SyntheticRanges, Casters);

TYPED_TEST(SyntheticRanges, BoxRoomAxisRaysHitInnerFaces) {
  const Pose2 origin{-2.0, 1.0, 0.0};
  const TypeParam caster(test::box_room(origin));
  const Point2 centre{origin.x + 2.5, origin.y + 2.5};
  for (const double angle : {0.0, pi / 2, pi, -pi / 2}) {
    EXPECT_NEAR(caster.cast_one(centre, angle, 10.0F), 2.0F, kTol) << "angle " << angle;
  }
}

TYPED_TEST(SyntheticRanges, BoxRoomObliqueAndCornerRays) {
  const TypeParam caster(test::box_room());
  // Slope 1/2 from (1.5, 2.5) meets the right face x = 4.5 at y = 4.0.
  EXPECT_NEAR(caster.cast_one({1.5, 2.5}, std::atan2(1.0, 2.0), 10.0F), std::sqrt(9.0 + 2.25),
              kTol);
  // The diagonal from the centre runs into the inner corner (4.5, 4.5).
  EXPECT_NEAR(caster.cast_one({2.5, 2.5}, pi / 4, 10.0F), 2.0 * std::sqrt(2.0), kTol);
  EXPECT_NEAR(caster.cast_one({2.5, 2.5}, -3 * pi / 4, 10.0F), 2.0 * std::sqrt(2.0), kTol);
}

TYPED_TEST(SyntheticRanges, MaxRangeClampsShortRays) {
  const TypeParam caster(test::box_room());
  EXPECT_EQ(caster.cast_one({2.5, 2.5}, 0.0, 1.25F), 1.25F);
}

TYPED_TEST(SyntheticRanges, RaysExactlyAlongGridLines) {
  const TypeParam caster(test::box_room());
  // Along the row line y = 2.0 and the column line x = 1.0, in the middle of the room.
  EXPECT_NEAR(caster.cast_one({1.0, 2.0}, 0.0, 10.0F), 3.5F, kTol);
  EXPECT_NEAR(caster.cast_one({1.0, 2.0}, pi / 2, 10.0F), 2.5F, kTol);
  EXPECT_NEAR(caster.cast_one({1.0, 2.0}, -pi / 2, 10.0F), 1.5F, kTol);
  EXPECT_NEAR(caster.cast_one({1.0, 2.0}, pi, 10.0F), 0.5F, kTol);
}

TYPED_TEST(SyntheticRanges, SingleWallBlocksOnlyItsSpan) {
  // One vertical wall in column 10 over rows 5..14 of a 2 m x 2 m grid of 0.1 m cells.
  std::vector<std::string> rows(20, std::string(20, '.'));
  for (int j = 5; j < 15; ++j) rows[static_cast<std::size_t>(19 - j)][10] = '#';
  const TypeParam caster(test::grid_from_rows(rows, 0.1));
  EXPECT_NEAR(caster.cast_one({0.25, 1.05}, 0.0, 5.0F), 0.75F, kTol);
  EXPECT_NEAR(caster.cast_one({1.95, 1.05}, pi, 5.0F), 0.85F, kTol);
  EXPECT_EQ(caster.cast_one({0.25, 0.35}, 0.0, 5.0F), 5.0F);  // passes below the wall
  EXPECT_EQ(caster.cast_one({0.25, 1.05}, pi, 5.0F), 5.0F);   // leaves the map: nothing beyond
}

TYPED_TEST(SyntheticRanges, StartInsideWallReadsZero) {
  const TypeParam caster(test::box_room());
  for (const double angle : {0.0, 0.3, pi / 2, 2.0, pi, -1.0}) {
    EXPECT_EQ(caster.cast_one({0.25, 0.25}, angle, 10.0F), 0.0F) << "angle " << angle;
    EXPECT_EQ(caster.cast_one({4.75, 2.6}, angle, 10.0F), 0.0F) << "angle " << angle;
  }
}

TYPED_TEST(SyntheticRanges, OriginOffTheMapTravelsToTheOuterFace) {
  const TypeParam caster(test::box_room());
  EXPECT_NEAR(caster.cast_one({-3.0, 2.6}, 0.0, 10.0F), 3.0F, kTol);
  EXPECT_NEAR(caster.cast_one({2.6, 8.0}, -pi / 2, 10.0F), 3.0F, kTol);
  EXPECT_EQ(caster.cast_one({-3.0, 2.6}, pi, 10.0F), 10.0F);
  EXPECT_EQ(caster.cast_one({-3.0, 7.0}, 0.0, 10.0F), 10.0F);  // misses the map
  EXPECT_EQ(caster.cast_one({-3.0, 2.6}, 0.0, 2.0F), 2.0F);    // wall beyond max_range
}

TYPED_TEST(SyntheticRanges, UnknownCellsBlockUnlessDisabled) {
  const auto grid = test::grid_from_rows({"..?...#", "..?...#", "..?...#"}, 1.0);
  RayCastOptions pass;
  pass.unknown_blocks = false;
  EXPECT_NEAR(TypeParam(grid).cast_one({0.5, 1.5}, 0.0, 20.0F), 1.5F, kTol);
  EXPECT_NEAR(TypeParam(grid, pass).cast_one({0.5, 1.5}, 0.0, 20.0F), 5.5F, kTol);
  EXPECT_EQ(TypeParam(grid).cast_one({2.5, 1.5}, 0.0, 20.0F), 0.0F);
  EXPECT_NEAR(TypeParam(grid, pass).cast_one({2.5, 1.5}, 0.0, 20.0F), 3.5F, kTol);
}

TYPED_TEST(SyntheticRanges, YawedOriginGivesTheSameRanges) {
  const Pose2 origin{3.0, -1.0, 0.7};
  const auto grid = test::box_room(origin);
  const TypeParam caster(grid);
  const auto at = [&grid](double gx, double gy) { return grid.to_map_frame({gx, gy}); };
  EXPECT_NEAR(caster.cast_one(at(2.5, 2.5), 0.7, 10.0F), 2.0F, kTol);
  EXPECT_NEAR(caster.cast_one(at(2.5, 2.5), 0.7 + pi / 2, 10.0F), 2.0F, kTol);
  EXPECT_NEAR(caster.cast_one(at(1.5, 2.5), 0.7 + std::atan2(1.0, 2.0), 10.0F),
              std::sqrt(9.0 + 2.25), kTol);
  EXPECT_EQ(caster.cast_one(at(0.25, 0.25), 0.0, 10.0F), 0.0F);
  EXPECT_NEAR(caster.cast_one(at(-3.0, 2.6), 0.7, 10.0F), 3.0F, kTol);
}

}  // namespace
}  // namespace mote
