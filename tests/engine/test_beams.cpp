#include "mote/engine/beams.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mote {
namespace {

LaserScan scan_of(std::vector<float> ranges) {
  LaserScan scan;
  scan.angle_min = -1.0F;
  scan.angle_increment = 0.1F;
  scan.range_min = 0.1F;
  scan.range_max = 10.0F;
  scan.ranges = std::move(ranges);
  return scan;
}

TEST(SelectBeams, DropsInvalidReadingsBeforeDecimating) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const LaserScan scan = scan_of({nan, 1.0F, -1.0F, 0.05F, 2.0F, 10.0F, inf, -inf, 3.0F, 4.0F});
  BeamSet beams;
  select_beams(scan, {.max_beams = 2}, beams);
  // Valid: 1.0 (i=1), 2.0 (i=4), 3.0 (i=8), 4.0 (i=9); decimated to survivors 0 and 2.
  EXPECT_EQ(beams.valid, 4U);
  ASSERT_EQ(beams.size(), 2U);
  EXPECT_FLOAT_EQ(beams.range[0], 1.0F);
  EXPECT_FLOAT_EQ(beams.range[1], 3.0F);
  EXPECT_FLOAT_EQ(beams.angle[0], static_cast<float>(scan.beam_angle(1)));
  EXPECT_FLOAT_EQ(beams.angle[1], static_cast<float>(scan.beam_angle(8)));
}

TEST(SelectBeams, KeepsMaxRangeReadingsWhenAsked) {
  const LaserScan scan = scan_of({1.0F, 10.0F, std::numeric_limits<float>::infinity(), 12.0F});
  BeamSet beams;
  select_beams(scan, {.max_beams = 60, .keep_max_range = true}, beams);
  ASSERT_EQ(beams.size(), 4U);
  for (std::size_t i = 1; i < 4; ++i) EXPECT_FLOAT_EQ(beams.range[i], 10.0F);
}

TEST(SelectBeams, ConfiguredRangesNeverWidenTheScans) {
  const LaserScan scan = scan_of({0.3F, 5.0F, 9.0F, 9.99F});
  BeamSet beams;
  select_beams(scan, {.max_beams = 60, .range_min = 0.5, .range_max = 100.0}, beams);
  EXPECT_FLOAT_EQ(beams.range_max, 10.0F);
  ASSERT_EQ(beams.size(), 3U);
  select_beams(scan, {.max_beams = 60, .range_min = 0.5, .range_max = 8.0}, beams);
  ASSERT_EQ(beams.size(), 1U);
  EXPECT_FLOAT_EQ(beams.range[0], 5.0F);
}

TEST(SelectBeams, DecimationIsEvenlySpaced) {
  std::vector<float> ranges(180, 5.0F);
  for (std::size_t i = 0; i < ranges.size(); ++i) ranges[i] = 1.0F + 0.01F * static_cast<float>(i);
  BeamSet beams;
  select_beams(scan_of(ranges), {.max_beams = 60}, beams);
  ASSERT_EQ(beams.size(), 60U);
  for (std::size_t k = 0; k < 60; ++k) EXPECT_FLOAT_EQ(beams.range[k], ranges[3 * k]);
}

TEST(SelectBeams, AllInvalidGivesNoBeams) {
  BeamSet beams;
  select_beams(scan_of({-1.0F, std::numeric_limits<float>::quiet_NaN(), 10.0F}), {}, beams);
  EXPECT_TRUE(beams.empty());
  EXPECT_EQ(beams.readings, 3U);
}

}  // namespace
}  // namespace mote
