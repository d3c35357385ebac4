// map.png on a global start: the estimate before the filter settled is drawn as dots, not as
// lines through walls, and the start marker is where the robot started (the reference) or,
// without one, the first settled estimate, labelled so.
#include <gtest/gtest.h>

#include <vector>

#include "mote/replay/map_image.hpp"
#include "mote/replay/report.hpp"

namespace mote::replay {
namespace {

using S = LocalizationState;

// 8 x 3 cells of 1 m: the middle row is a wall between the free bottom and top rows.
OccupancyGrid walled_map() {
  std::vector<CellState> cells(24, CellState::kFree);
  for (std::size_t i = 8; i < 16; ++i) cells[i] = CellState::kOccupied;
  return OccupancyGrid(8, 3, 1.0, Pose2{}, cells);
}

// A global start: one guess at the top row's right end (uncertain), then five tracking updates
// along the bottom row's left half, one per second from stamp 10 s.
ReplayResult global_run() {
  ReplayResult r{walled_map(), LocalizerConfig{}};
  r.global_start = true;
  r.first_stamp = 10.0;
  const std::vector<Pose2> poses{{6.5, 2.5, 0.0}, {0.5, 0.5, 0.0},  {1.25, 0.5, 0.0},
                                 {2.0, 0.5, 0.0}, {2.75, 0.5, 0.0}, {3.5, 0.5, 0.0}};
  for (std::size_t k = 0; k < poses.size(); ++k) {
    UpdateRecord u;
    u.stamp = 10.0 + static_cast<double>(k);
    u.state = k == 0 ? S::kUncertain : S::kTracking;
    r.updates.push_back(u);
    r.trajectory.push_back({u.stamp, poses[k]});
  }
  return r;
}

std::vector<S> states_of(const ReplayResult& r) {
  std::vector<S> s;
  for (const UpdateRecord& u : r.updates) s.push_back(u.state);
  return s;
}

TEST(MapOverlay, AGlobalStartIsMarkedAtTheFirstSettledEstimateWithoutAReference) {
  const ReplayResult r = global_run();
  const std::vector<S> states = states_of(r);
  const MapOverlay o = map_overlay(r, states);
  EXPECT_EQ(o.settled, 1U);
  ASSERT_TRUE(o.start.has_value());
  EXPECT_DOUBLE_EQ(o.start->x, 0.5);
  EXPECT_DOUBLE_EQ(o.start->y, 0.5);
  EXPECT_EQ(o.start_label, "first settled estimate");
}

TEST(MapOverlay, WithAReferenceTheStartIsWhereTheRobotStarted) {
  ReplayResult r = global_run();
  r.reference = {{11.0, {2.0, 0.5, 0.0}}, {10.0, {3.5, 0.5, 0.0}}};
  const std::vector<S> states = states_of(r);
  const MapOverlay o = map_overlay(r, states);
  ASSERT_TRUE(o.start.has_value());
  EXPECT_DOUBLE_EQ(o.start->x, 3.5);  // the pose at the first scan's stamp, not the file's first
  EXPECT_EQ(o.start_label, "start (reference)");
}

TEST(MapOverlay, ARunThatTracksFromItsFirstUpdateIsSettledThere) {
  ReplayResult r = global_run();
  r.updates.front().state = S::kTracking;
  EXPECT_EQ(settled_index(r), 0U);
  r.updates[3].state = S::kLost;  // tracking on 1-2 only, then 4-5 to the end
  r.updates.front().state = S::kUncertain;
  EXPECT_EQ(settled_index(r), 4U);
}

TEST(MapOverlay, TheEstimateBeforeItSettledIsNotALineThroughTheWall) {
  const ReplayResult r = global_run();
  const std::vector<S> states = states_of(r);
  MapRenderOptions options;
  options.target_pixels = 80;  // 10 pixels per cell
  options.max_scale = 10;
  MapFigure f = render_map(r.map(), map_overlay(r, states), options);
  ASSERT_EQ(f.scale, 10);
  const auto pixel = [&](int x, int y) { return f.image.at(f.map_area.x + x, f.map_area.y + y); };
  // The guess in the top row is a red dot; the wall between it and the bottom row stays black
  // where the jump would cross it; the settled path along the bottom row is a red line.
  EXPECT_GT(pixel(65, 5)[0], 200);
  EXPECT_LT(pixel(65, 5)[1], 50);
  EXPECT_EQ(pixel(35, 15)[0], 0);
  EXPECT_GT(pixel(20, 25)[0], 200);
  EXPECT_LT(pixel(20, 25)[1], 50);
}

}  // namespace
}  // namespace mote::replay
