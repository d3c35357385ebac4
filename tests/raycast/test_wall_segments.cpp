// The wall segments Embree's scene is built from: every cell edge between blocking and
// non-blocking cells, merged into maximal runs, in one order for any thread count.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "mote/maps/map_loader.hpp"
#include "mote_test/data.hpp"
#include "ray_setup.hpp"
#include "wall_segments.hpp"

namespace mote {
namespace {

using detail::CellMask;
using detail::WallSegment;

// A unit edge: (horizontal?, line, cell along the line).
using UnitEdge = std::tuple<bool, int, int>;

std::set<UnitEdge> unit_edges(const std::vector<WallSegment>& walls, float resolution) {
  std::set<UnitEdge> edges;
  const auto cell = [&](float v) { return static_cast<int>(std::lround(v / resolution)); };
  for (const WallSegment& s : walls) {
    const bool horizontal = s.y0 == s.y1;
    const int line = horizontal ? cell(s.y0) : cell(s.x0);
    const int begin = horizontal ? cell(s.x0) : cell(s.y0);
    const int end = horizontal ? cell(s.x1) : cell(s.y1);
    for (int k = begin; k < end; ++k) {
      EXPECT_TRUE(edges.insert({horizontal, line, k}).second) << "an edge in two segments";
    }
  }
  return edges;
}

std::set<UnitEdge> boundary_edges(const CellMask& mask) {
  std::set<UnitEdge> edges;
  for (int j = 0; j <= mask.height; ++j) {
    for (int i = 0; i < mask.width; ++i) {
      if (mask.blocks_or_free(i, j - 1) != mask.blocks_or_free(i, j)) edges.insert({true, j, i});
    }
  }
  for (int i = 0; i <= mask.width; ++i) {
    for (int j = 0; j < mask.height; ++j) {
      if (mask.blocks_or_free(i - 1, j) != mask.blocks_or_free(i, j)) edges.insert({false, i, j});
    }
  }
  return edges;
}

TEST(WallSegments, CoverEveryBoundaryEdgeOnceInMaximalRuns) {
  // Wider and taller than one block of lines, blocking cells in clumps and alone.
  const int w = 600;
  const int h = 530;
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h);
  std::mt19937 rng(3);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    cells[k] = (rng() % 7 == 0 || (k / 40) % 5 == 0) ? 1 : 0;
  }
  const CellMask mask{w, h, 0.05F, cells.data()};
  std::vector<WallSegment> walls;
  tbb::task_arena(2).execute([&] { walls = detail::wall_segments(mask); });
  EXPECT_EQ(unit_edges(walls, mask.resolution), boundary_edges(mask));
  // Maximal: no segment ends where another on the same line begins.
  std::set<std::tuple<bool, float, float>> starts;
  for (const WallSegment& s : walls)
    starts.insert({s.y0 == s.y1, s.y0 == s.y1 ? s.y0 : s.x0, s.y0 == s.y1 ? s.x0 : s.y0});
  for (const WallSegment& s : walls) {
    const bool horizontal = s.y0 == s.y1;
    EXPECT_EQ(starts.count({horizontal, horizontal ? s.y1 : s.x1, horizontal ? s.x1 : s.y1}), 0U);
  }
}

TEST(WallSegments, TheListIsTheSameForAnyThreadCount) {
  MOTE_REQUIRE_DATA(path, "intel/intel.yaml");
  const OccupancyGrid grid = load_map(path);
  const std::vector<std::uint8_t> blocking = detail::blocking_mask(grid, false);
  const CellMask mask{grid.width(), grid.height(), static_cast<float>(grid.resolution()),
                      blocking.data()};
  std::vector<WallSegment> one;
  std::vector<WallSegment> two;
  tbb::task_arena(1).execute([&] { one = detail::wall_segments(mask); });
  tbb::task_arena(2).execute([&] { two = detail::wall_segments(mask); });
  ASSERT_EQ(one.size(), two.size());
  ASSERT_GT(one.size(), 1000U);
  for (std::size_t k = 0; k < one.size(); ++k) {
    ASSERT_EQ(std::tie(one[k].x0, one[k].y0, one[k].x1, one[k].y1),
              std::tie(two[k].x0, two[k].y0, two[k].x1, two[k].y1))
        << "segment " << k;
  }
}

}  // namespace
}  // namespace mote
