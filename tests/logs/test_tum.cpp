/// \file
/// TUM trajectory reading and writing.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "mote/core/error.hpp"
#include "mote/logs/tum.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::logs {
namespace {

TEST(Tum, ReadsTheIntelReferencePoses) {
  MOTE_REQUIRE_DATA(path, "intel/intel.gt.tum");
  const std::vector<StampedPose> poses = read_tum(path);
  ASSERT_EQ(poses.size(), 910U);
  // First line: 32.906800 0.600266 -0.032033 0 0 0 -0.176404537 0.984317753
  EXPECT_DOUBLE_EQ(poses.front().stamp, 32.9068);
  EXPECT_DOUBLE_EQ(poses.front().pose.x, 0.600266);
  EXPECT_DOUBLE_EQ(poses.front().pose.y, -0.032033);
  EXPECT_NEAR(poses.front().pose.theta, 2.0 * std::atan2(-0.176404537, 0.984317753), 1e-12);
}

TEST(Tum, WriteThenReadRoundTrips) {
  std::vector<StampedPose> poses;
  for (int i = 0; i < 50; ++i) {
    const double k = static_cast<double>(i);
    poses.push_back(
        {1510757286.108764922 + 0.0371 * k, {0.5 * k - 3.0, -0.25 * k, wrap_angle(0.4 * k)}});
  }
  std::stringstream s;
  write_tum(s, poses);
  const std::vector<StampedPose> back = read_tum(s, "memory");
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back[i].stamp, poses[i].stamp, 1e-9);  // %.9f: ns
    EXPECT_NEAR(back[i].pose.x, poses[i].pose.x, 1e-6);
    EXPECT_NEAR(back[i].pose.y, poses[i].pose.y, 1e-6);
    EXPECT_NEAR(std::abs(wrap_angle(back[i].pose.theta - poses[i].pose.theta)), 0.0, 1e-8);
  }
}

TEST(Tum, SkipsCommentsAndBlankLines) {
  std::stringstream s("# header\n\n1.5 2 3 0 0 0 0.7071067811865476 0.7071067811865476\n");
  const auto poses = read_tum(s, "memory");
  ASSERT_EQ(poses.size(), 1U);
  EXPECT_NEAR(poses[0].pose.theta, std::numbers::pi / 2, 1e-12);
}

void expect_error(const std::string& text, const std::string& place, const std::string& what) {
  std::stringstream s(text);
  try {
    (void)read_tum(s, "traj.tum");
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "traj.tum");
    EXPECT_EQ(e.place(), place);
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(Tum, RejectsMalformedLinesWithFileAndLine) {
  const std::string good = "1 0 0 0 0 0 0 1\n";
  expect_error(good + "2 0 0 0 0 0 1\n", "line 2", "expected 8 more fields");
  expect_error(good + good + "3 0 0 0 0 0 0 1 9\n", "line 3", "found 9");
  expect_error("1 abc 0 0 0 0 0 1\n", "line 1", "field 'x'");
  expect_error("1 0 nan 0 0 0 0 1\n", "line 1", "finite");
  expect_error("inf 0 0 0 0 0 0 1\n", "line 1", "timestamp");
  expect_error("1 0 0 0 0 0 0 0\n", "line 1", "zero length");
  expect_error("1 0 0 0 0 0 0 1.0x\n", "line 1", "qw");
}

TEST(Tum, MissingFileIsAnInputError) {
  EXPECT_THROW((void)read_tum(std::filesystem::path("/nonexistent/traj.tum")), InputError);
}

}  // namespace
}  // namespace mote::logs
