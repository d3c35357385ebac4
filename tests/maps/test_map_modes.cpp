// map_server's pixel rules on in-memory images (values worked by hand from image_loader.cpp).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"

namespace mote {
namespace {

MapMetadata meta(MapMode mode, bool negate = false) {
  MapMetadata m;
  m.resolution = 0.1;
  m.mode = mode;
  m.negate = negate;
  return m;
}

int value(std::vector<std::uint16_t> pixel, const MapMetadata& m, std::uint32_t maxval = 255) {
  MapImage image;
  image.width = 1;
  image.height = 1;
  image.channels = static_cast<int>(pixel.size());
  image.maxval = maxval;
  image.samples = pixel;
  return map_server_value(image, image.samples.data(), m);
}

TEST(MapServerValue, TrinaryGray) {
  const MapMetadata m = meta(MapMode::kTrinary);
  EXPECT_EQ(value({0}, m), 100);
  EXPECT_EQ(value({255}, m), 0);
  EXPECT_EQ(value({205}, m), -1);  // occ = 50/255 = 0.19608, just above free_thresh 0.196
  EXPECT_EQ(value({206}, m), 0);   // occ = 0.19216
  EXPECT_EQ(value({89}, m), 100);  // occ = 0.65098 > 0.65
  EXPECT_EQ(value({90}, m), -1);   // occ = 0.64706
}

TEST(MapServerValue, NegateSwapsBlackAndWhite) {
  const MapMetadata m = meta(MapMode::kTrinary, true);
  EXPECT_EQ(value({0}, m), 0);
  EXPECT_EQ(value({255}, m), 100);
}

TEST(MapServerValue, ScaleGradesTheMiddle) {
  const MapMetadata m = meta(MapMode::kScale);
  EXPECT_EQ(value({205}, m), 1);   // 1 + 98 * (0.19608 - 0.196) / 0.454
  EXPECT_EQ(value({128}, m), 66);  // occ = 127/255 = 0.49804, ratio 0.66528
  EXPECT_EQ(value({128, 128, 128, 255}, m), 66);
  EXPECT_EQ(value({128, 128, 128, 0}, m), -1);  // transparent in-between pixel
  EXPECT_EQ(value({255, 255, 255, 0}, m), 0);   // scale mode ignores alpha in the average
}

TEST(MapServerValue, TrinaryAveragesAlphaWithColours) {
  const MapMetadata m = meta(MapMode::kTrinary);
  EXPECT_EQ(value({255, 255, 255, 0}, m), -1);  // mean 191.25 -> occ 0.25
  EXPECT_EQ(value({255, 255, 255, 255}, m), 0);
  EXPECT_EQ(value({255, 0, 0}, m), 100);  // mean 85 -> occ 0.667
  EXPECT_EQ(value({255, 255}, m), 0);     // gray + opaque alpha
}

TEST(MapServerValue, RawKeepsThePixel) {
  const MapMetadata m = meta(MapMode::kRaw);
  EXPECT_EQ(value({0}, m), 0);
  EXPECT_EQ(value({100}, m), 100);
  EXPECT_EQ(value({57}, m), 57);
  EXPECT_EQ(value({101}, m), -1);
  EXPECT_EQ(value({255}, m), -1);
}

TEST(MapServerValue, SixteenBitSamplesScaleToEightBit) {
  const MapMetadata m = meta(MapMode::kTrinary);
  EXPECT_EQ(value({0}, m, 65535), 100);
  EXPECT_EQ(value({65535}, m, 65535), 0);
  EXPECT_EQ(value({52685}, m, 65535), -1);  // 205 * 257
  EXPECT_EQ(value({1}, m, 1), 0);           // a 1-bit-deep PGM: white
}

TEST(GridFromImage, FlipsRowsAndReadsRawValuesLikeAmcl) {
  MapImage image;
  image.width = 3;
  image.height = 2;
  image.samples = {0,   100, 50,  // top row
                   255, 0,   100};
  const OccupancyGrid grid = grid_from_image(image, meta(MapMode::kRaw));
  EXPECT_EQ(grid.at({0, 1}), CellState::kFree);
  EXPECT_EQ(grid.at({1, 1}), CellState::kOccupied);
  EXPECT_EQ(grid.at({2, 1}), CellState::kUnknown);  // 50: neither 0 nor 100
  EXPECT_EQ(grid.at({0, 0}), CellState::kUnknown);
  EXPECT_EQ(grid.at({1, 0}), CellState::kFree);
  EXPECT_EQ(grid.at({2, 0}), CellState::kOccupied);
  EXPECT_EQ(grid.free_cells(), (std::vector<std::uint32_t>{1, 3}));
}

TEST(GridFromImage, RejectsInconsistentImages) {
  MapImage image;
  image.width = 2;
  image.height = 2;
  image.samples = {1, 2, 3};
  EXPECT_THROW((void)grid_from_image(image, meta(MapMode::kTrinary), "mem"), InputError);
}

}  // namespace
}  // namespace mote
