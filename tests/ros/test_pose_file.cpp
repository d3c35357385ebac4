#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

#include "mote/core/error.hpp"
#include "pose_file.hpp"

namespace mote::ros {
namespace {

namespace fs = std::filesystem;

struct Captured {
  std::string text;
  detail::WarningLog log{[this](const std::string& l) { text += l + "\n"; },
                         std::chrono::seconds(0)};
};

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("mote_pose_file_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir / name;
}

TEST(PoseFile, WhatIsWrittenIsReadBack) {
  const fs::path path = scratch("pose.yaml");
  write_pose_file(path, Pose2{1.25, -3.5, 0.75}, 1663967418.2);
  Captured c;
  const std::optional<Pose2> p = read_pose_file(path, c.log);
  ASSERT_TRUE(p.has_value()) << c.text;
  EXPECT_NEAR(p->x, 1.25, 1e-6);
  EXPECT_NEAR(p->y, -3.5, 1e-6);
  EXPECT_NEAR(p->theta, 0.75, 1e-6);
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));  // renamed over the file, not left beside it
}

// A crash while writing leaves the temporary file half written; the file itself is the last
// complete one, because it is only ever replaced by a rename.
TEST(PoseFile, AWriteCutShortLeavesThePreviousPoseWhole) {
  const fs::path path = scratch("cut.yaml");
  write_pose_file(path, Pose2{2.0, 3.0, 0.5}, 10.0);
  std::ofstream(path.string() + ".tmp") << "x: 9.0\ny: ";  // what a crash mid-write leaves
  Captured c;
  const std::optional<Pose2> p = read_pose_file(path, c.log);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->x, 2.0, 1e-9);
  write_pose_file(path, Pose2{4.0, 5.0, 0.0}, 11.0);  // the next write replaces the leftover
  EXPECT_NEAR(read_pose_file(path, c.log)->x, 4.0, 1e-9);
}

TEST(PoseFile, AMissingOrMalformedFileIsNoPoseAndSaysWhy) {
  Captured c;
  EXPECT_FALSE(read_pose_file(scratch("absent.yaml"), c.log).has_value());
  EXPECT_NE(c.text.find("no saved pose"), std::string::npos) << c.text;
  const fs::path bad = scratch("bad.yaml");
  std::ofstream(bad) << "x: 1.0\ny: nan\nyaw: 0\n";
  EXPECT_FALSE(read_pose_file(bad, c.log).has_value());
  EXPECT_NE(c.text.find("expected finite x:, y: and yaw:"), std::string::npos) << c.text;
}

TEST(PoseFile, AFolderThatCannotBeWrittenIsAnError) {
  EXPECT_THROW(write_pose_file("/proc/mote-no-such-dir/pose.yaml", Pose2{}, 0.0), Error);
}

}  // namespace
}  // namespace mote::ros
