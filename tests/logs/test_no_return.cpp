// The laser's no-return reading inferred from CARMEN FLASER logs (no_return.hpp): synthetic logs
// with 50 m and 81.83 m codes and one without any, the overrides, and the recorded logs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/logs/no_return.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::logs {
namespace {

using test::read_all;

// A FLASER log of `scans` 180-beam scans of a robot driving along x, 5 cm per scan: readings of
// 0.5..8 m at centimetre resolution varying with the pose, and beam 45 at a far wall it drives
// away from (25 m - 0.4 x, so each pose has its own largest reading); in every
// `code_every`-th scan a doorway of beams 80..89 sees nothing and reads `code` (no code when
// code_every = 0). The first `standing` scans are taken without moving, all alike.
std::string flaser_log(std::size_t scans, const std::string& code, std::size_t code_every,
                       std::size_t standing = 0) {
  std::string text = "# synthetic\n";
  const auto cm = [](double r) { return std::to_string(std::round(r * 100.0) / 100.0); };
  for (std::size_t s = 0; s < scans; ++s) {
    const double x = s < standing ? 0.0 : 0.05 * static_cast<double>(s - standing + 1);
    std::string line = "FLASER 180";
    for (int b = 0; b < 180; ++b) {
      const bool open = code_every != 0 && s % code_every == 0 && b >= 80 && b < 90;
      const double r =
          b == 45 ? 25.0 - 0.4 * x : 0.5 + std::fmod(7.31 * b + 3.7 * x + 0.013 * b * b, 7.5);
      line += " " + (open ? code : cm(r));
    }
    const std::string pose = " " + std::to_string(x) + " 0 0";
    line += pose + pose + " " + std::to_string(10.0 + 0.1 * static_cast<double>(s)) + " h 0\n";
    text += line;
  }
  return text;
}

std::vector<ScanFrame> read_text(const std::string& text, ReaderOptions options = {}) {
  const auto path = test::temp_dir() / "log.clf";
  test::write_bytes(path, text);
  auto source = open_scan_log(path, options);
  return read_all(*source);
}

float max_range_of(const std::string& text, std::string* source_text = nullptr) {
  const auto path = test::temp_dir() / "log.clf";
  test::write_bytes(path, text);
  auto source = open_scan_log(path);
  const auto frames = read_all(*source);
  for (const ScanFrame& f : frames) EXPECT_EQ(f.scan.range_max, frames.front().scan.range_max);
  if (source_text != nullptr) *source_text = source->range_max_source();
  return frames.front().scan.range_max;
}

TEST(NoReturn, InfersA50MetreCode) {
  std::string why;
  EXPECT_EQ(max_range_of(flaser_log(300, "50.00", 7), &why), 50.0F);
  EXPECT_NE(why.find("inferred"), std::string::npos) << why;
}

TEST(NoReturn, InfersTheSickCodeFromFewScans) {
  // As on Wean Hall: the code tops only 3 of the first 200 moving scans.
  EXPECT_EQ(max_range_of(flaser_log(300, "81.83", 70)), 81.83F);
  // A rarer larger value (SICK's 81.91 "dazzled") does not hide the code.
  std::string text = flaser_log(300, "81.83", 5);
  const auto at = text.find(" 81.83", text.find("FLASER", 200));
  text.replace(at, 6, " 81.91");
  EXPECT_EQ(max_range_of(text), 81.83F);
}

TEST(NoReturn, WithoutACodeEveryReadingStaysValid) {
  const auto frames = read_text(flaser_log(300, "", 0));
  float top = 0.0F;
  for (const ScanFrame& f : frames) {
    for (const float r : f.scan.ranges) top = std::max(top, r);
  }
  const float range_max = frames.front().scan.range_max;
  EXPECT_GT(range_max, top);
  EXPECT_LT(range_max, top * 1.02F);
}

TEST(NoReturn, AStandingRobotDoesNotFakeACode) {
  // 150 identical scans at the start repeat their largest (real) reading, 25 m, the largest of
  // the log; counted 150 times it would pass for a code. Only moving scans count.
  const auto frames = read_text(flaser_log(400, "", 0, 150));
  EXPECT_FLOAT_EQ(frames.front().scan.ranges[45], 25.0F);
  EXPECT_GT(frames.front().scan.range_max, 25.0F);
}

TEST(NoReturn, GivenValueWins) {
  ReaderOptions options;
  options.carmen_max_range = 30.0F;
  const auto path = test::temp_dir() / "log.clf";
  test::write_bytes(path, flaser_log(50, "50.00", 7));
  auto source = open_scan_log(path, options);
  const auto frames = read_all(*source);
  EXPECT_EQ(frames.front().scan.range_max, 30.0F);
  EXPECT_NE(source->range_max_source().find("given"), std::string::npos);
}

TEST(NoReturn, AnErrorInTheFirstScansComesAfterTheFramesBeforeIt) {
  const auto path = test::temp_dir() / "log.clf";
  test::write_bytes(path, flaser_log(5, "50.00", 2) + "FLASER 180 1 2\n" + flaser_log(5, "", 0));
  auto source = open_scan_log(path);
  for (int k = 0; k < 5; ++k) {
    const auto frame = source->next();
    ASSERT_TRUE(frame.has_value());
    EXPECT_EQ(frame->scan.range_max, 50.0F);
  }
  EXPECT_THROW((void)source->next(), InputError);
}

TEST(NoReturn, IntelLogIsTheSickCode) {
  MOTE_REQUIRE_DATA(path, "intel/intel.clf");
  auto source = open_scan_log(path);
  const auto frames = read_all(*source);
  EXPECT_EQ(frames.front().scan.range_max, 81.83F);
  EXPECT_EQ(frames.back().scan.range_max, 81.83F);
  EXPECT_NE(source->range_max_source().find("inferred"), std::string::npos);
}

TEST(NoReturn, WeanLogRecordsItAndInferenceAgrees) {
  MOTE_REQUIRE_DATA(path, "wean/robotdata1.clf");
  auto source = open_scan_log(path);
  const auto frames = read_all(*source);
  EXPECT_EQ(frames.front().scan.range_max, 81.83F);  // ROBOTLASER1 max_range
  EXPECT_NE(source->range_max_source().find("ROBOTLASER1"), std::string::npos);
  NoReturnEstimator estimator;
  for (const ScanFrame& f : frames) {
    if (estimator.scans() < 200) estimator.add(f.scan.ranges, f.odometry);
  }
  const NoReturnRange found = estimator.estimate();
  EXPECT_TRUE(found.repeated);
  EXPECT_EQ(found.range_max, 81.83F);
}

}  // namespace
}  // namespace mote::logs
