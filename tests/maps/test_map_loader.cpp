// The loader on the recorded maps in ../shared/data. Expected counts and cells were found with an
// independent Python script (zlib + PNG unfiltering / raw PGM bytes, map_server's rule
// occ = (255 - mean(pixel)) / 255 with thresholds 0.65 / 0.196), reading image pixel
// (col, row) and mapping it to grid cell (col, height - 1 - row).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

struct KnownCell {
  int col;  ///< image column
  int row;  ///< image row (0 at the top)
  CellState state;
};

struct MapCase {
  const char* yaml;
  int width;
  int height;
  std::size_t occupied;
  std::size_t free;
  KnownCell cells[3];
};

std::size_t count(const OccupancyGrid& grid, CellState state) {
  std::size_t n = 0;
  for (const CellState c : grid.cells()) n += c == state ? 1 : 0;
  return n;
}

class RecordedMap : public ::testing::TestWithParam<MapCase> {};

TEST_P(RecordedMap, MatchesPixelsReadIndependently) {
  const MapCase& m = GetParam();
  MOTE_REQUIRE_DATA(path, m.yaml);
  const OccupancyGrid grid = load_map(path);
  ASSERT_EQ(grid.width(), m.width);
  ASSERT_EQ(grid.height(), m.height);
  EXPECT_EQ(count(grid, CellState::kOccupied), m.occupied);
  EXPECT_EQ(count(grid, CellState::kFree), m.free);
  EXPECT_EQ(grid.free_cell_count(), m.free);
  for (const KnownCell& k : m.cells) {
    const CellIndex c{k.col, m.height - 1 - k.row};
    EXPECT_EQ(grid.at(c), k.state) << "image pixel (" << k.col << ", " << k.row << ")";
  }
}

TEST_P(RecordedMap, CellCentresRoundTrip) {
  const MapCase& m = GetParam();
  MOTE_REQUIRE_DATA(path, m.yaml);
  const OccupancyGrid grid = load_map(path);
  for (const CellIndex c : {CellIndex{0, 0}, CellIndex{m.width - 1, 0}, CellIndex{0, m.height - 1},
                            CellIndex{m.width / 2, m.height / 3}}) {
    EXPECT_EQ(grid.world_to_cell(grid.cell_center(c)), c);
  }
}

constexpr auto kO = CellState::kOccupied;
constexpr auto kF = CellState::kFree;
constexpr auto kU = CellState::kUnknown;

INSTANTIATE_TEST_SUITE_P(
    SharedData, RecordedMap,
    ::testing::Values(MapCase{"intel/intel.yaml",
                              814,
                              760,
                              14405,
                              191018,
                              {{272, 254, kF}, {290, 254, kU}, {295, 254, kO}}},
                      MapCase{"wean/wean_map.yaml",
                              800,
                              800,
                              20264,
                              48059,
                              {{267, 267, kU}, {398, 267, kO}, {403, 267, kF}}},
                      MapCase{"dis/dis_underground.yaml",
                              1209,
                              1151,
                              4863,
                              85737,
                              {{404, 384, kU}, {820, 384, kO}, {821, 384, kF}}},
                      MapCase{"maps/basement_fixed.map.yaml",
                              1300,
                              1300,
                              14374,
                              275742,
                              {{434, 434, kF}, {502, 434, kO}, {504, 434, kU}}},
                      MapCase{"maps/willow-full-0.05.yaml",
                              1165,
                              945,
                              13459,
                              549308,
                              {{389, 316, kU}, {413, 316, kF}, {450, 316, kO}}},
                      MapCase{"maps/turtlebot3_world.yaml",
                              384,
                              384,
                              870,
                              7903,
                              {{129, 129, kU}, {178, 132, kO}, {180, 133, kF}}}));

TEST(MapLoader, BasementYawTurnsTheMapAroundItsOrigin) {
  MOTE_REQUIRE_DATA(path, "maps/basement_fixed.map.yaml");
  const OccupancyGrid grid = load_map(path);
  EXPECT_DOUBLE_EQ(grid.resolution(), 0.0504);
  EXPECT_DOUBLE_EQ(grid.origin().theta, 3.14);
  // Yaw 3.14 is nearly a half turn: the 65.52 m square extends to -x and -y of the origin
  // (25.9, 48.5), with sin(3.14) * 65.52 m = 0.10 m of skew.
  const double side = 1300 * 0.0504;
  const Bounds2 b = grid.bounds();
  EXPECT_NEAR(b.max_x, 25.9, 0.11);
  EXPECT_NEAR(b.max_y, 48.5, 0.11);
  EXPECT_NEAR(b.min_x, 25.9 - side, 0.11);
  EXPECT_NEAR(b.min_y, 48.5 - side, 0.11);
  // The lower-left pixel's corner is the origin, so the first cell centre lies at -x, -y of it.
  const Point2 first = grid.cell_center({0, 0});
  EXPECT_NEAR(first.x, 25.9 - 0.0252, 1e-3);
  EXPECT_NEAR(first.y, 48.5 - 0.0252, 1e-3);
}

TEST(MapLoader, RelativeImagePathResolvesAgainstTheYamlFolder) {
  MOTE_REQUIRE_DATA(path, "maps/turtlebot3_world.yaml");
  const MapMetadata meta = read_map_metadata(path);
  EXPECT_EQ(meta.image, path.parent_path() / "turtlebot3_world.pgm");
  EXPECT_EQ(meta.mode, MapMode::kTrinary);
  EXPECT_DOUBLE_EQ(meta.origin.x, -10.0);
  EXPECT_DOUBLE_EQ(meta.free_thresh, 0.196);
}

}  // namespace
}  // namespace mote
