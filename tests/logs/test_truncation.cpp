/// \file
/// Truncated and byte-flipped copies of real and built logs: strict readers either read or throw
/// InputError; lenient readers keep the readable part and say how much they skipped.

#include <gtest/gtest.h>

#include <random>

#include "bag_builder.hpp"
#include "mote/core/error.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::logs {
namespace {

struct Outcome {
  std::size_t frames = 0;
  bool threw = false;
  ReadStats stats;
};

Outcome read_copy(const std::filesystem::path& path, const std::string& bytes, bool lenient) {
  test::write_bytes(path, bytes);
  ReaderOptions options;
  options.lenient = lenient;
  Outcome out;
  try {
    auto source = open_scan_log(path, options);
    while (source->next()) ++out.frames;
    out.stats = source->stats();
  } catch (const InputError&) {
    out.threw = true;
  }
  return out;
}

/// Cut points spread over the file, not on record boundaries by construction.
std::vector<std::size_t> cut_points(std::size_t size, int count) {
  std::vector<std::size_t> cuts;
  for (int k = 1; k <= count; ++k) {
    cuts.push_back(size * static_cast<std::size_t>(k) / static_cast<std::size_t>(count + 1) + 7);
  }
  return cuts;
}

TEST(Truncation, CarmenLenientReadsThePrefix) {
  MOTE_REQUIRE_DATA(path, "intel/intel.clf");
  const std::string log = test::read_bytes(path);
  const auto copy = test::temp_dir() / "cut.clf";
  std::size_t previous = 0;
  for (std::size_t cut : cut_points(log.size(), 12)) {
    const Outcome lenient = read_copy(copy, log.substr(0, cut), true);
    ASSERT_FALSE(lenient.threw);
    EXPECT_GE(lenient.frames, previous);
    EXPECT_LT(lenient.frames, 910U);
    previous = lenient.frames;
    // A cut inside a line leaves at most that line malformed (a cut inside the last number
    // can still leave a valid line); strict mode throws exactly when lenient mode skips.
    const bool mid_line = log[cut - 1] != '\n';
    EXPECT_LE(lenient.stats.records_skipped, mid_line ? 1U : 0U) << cut;
    const Outcome strict = read_copy(copy, log.substr(0, cut), false);
    EXPECT_EQ(strict.threw, lenient.stats.records_skipped == 1U) << cut;
  }
}

TEST(Truncation, BagLenientReadsThePrefixAndStrictThrows) {
  MOTE_REQUIRE_DATA(path, "dis/dis-underground.bag");
  const std::string bag = test::read_bytes(path);
  const auto copy = test::temp_dir() / "cut.bag";
  std::size_t previous = 0;
  for (std::size_t cut : cut_points(bag.size(), 6)) {
    const Outcome lenient = read_copy(copy, bag.substr(0, cut), true);
    ASSERT_FALSE(lenient.threw) << cut;
    EXPECT_GE(lenient.frames, previous);
    EXPECT_LT(lenient.frames, 4427U);
    EXPECT_GT(lenient.stats.bytes_skipped, 0U);
    EXPECT_EQ(lenient.stats.records_skipped, 1U);
    previous = lenient.frames;
    EXPECT_TRUE(read_copy(copy, bag.substr(0, cut), false).threw) << cut;
  }
  EXPECT_GT(previous, 3000U);
}

TEST(Truncation, SmallBagCutAtEveryByteNeverCrashes) {
  test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/tf", "tf2_msgs/TFMessage");
  b.message(1, 1, 0, test::tf_message(1, 0, "odom", "base", 0.0, 0.0, 0.0));
  b.message(0, 1, 0, test::scan_message(1, 0, "base", {1.0F, 2.0F}));
  b.message(1, 2, 0, test::tf_message(2, 0, "odom", "base", 1.0, 0.0, 0.0));
  const auto copy = test::temp_dir() / "cut.bag";
  for (const char* kind : {"none", "bz2", "lz4"}) {
    const std::string bag = b.finish(kind);
    EXPECT_EQ(read_copy(copy, bag, false).frames, 1U);
    for (std::size_t cut = 0; cut < bag.size(); ++cut) {
      (void)read_copy(copy, bag.substr(0, cut), false);
      const Outcome lenient = read_copy(copy, bag.substr(0, cut), true);
      EXPECT_LE(lenient.frames, 1U);
    }
  }
}

/// The message of the InputError strict reading of `bytes` (written to `path`) throws.
std::string strict_error(const std::filesystem::path& path, const std::string& bytes) {
  test::write_bytes(path, bytes);
  try {
    auto source = open_scan_log(path, ReaderOptions{});
    while (source->next()) {
    }
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string carmen_scan(int stamp) {
  std::string line = "FLASER 180";
  for (int i = 0; i < 180; ++i) line += " 1.5";
  return line + " 1 2 0.5 1 2 0.5 " + std::to_string(stamp) + " host " + std::to_string(stamp) +
         "\n";
}

// Issue 48: a .clf cut inside its last line (a copy or recording interrupted) says so and names
// --lenient, as a cut MCAP file does; a malformed line that is not the cut one does not.
TEST(Truncation, ACutCarmenLogSaysCutShortAndNamesLenient) {
  const std::string log = "ODOM 1 2 0.5 0 0 0 1 host 1\n" + carmen_scan(1) + carmen_scan(2) +
                          carmen_scan(3) + carmen_scan(4);
  const auto path = test::temp_dir() / "cut.clf";
  const std::string cut = strict_error(path, log.substr(0, log.size() - 500));
  EXPECT_NE(cut.find(path.string() + ": line 5: FLASER/RLASER ranges and poses: expected"),
            std::string::npos)
      << cut;
  EXPECT_NE(cut.find("(the file ends inside this line: cut short? --lenient reads the 3 scans "
                     "before it)"),
            std::string::npos)
      << cut;
  const std::string malformed = strict_error(path, log.substr(0, log.size() - 500) + "\n");
  EXPECT_NE(malformed.find("line 5: FLASER/RLASER"), std::string::npos) << malformed;
  EXPECT_EQ(malformed.find("cut short"), std::string::npos) << malformed;
}

// Issue 48: a .bag cut in a record (its header places the index past the cut) says so and names
// --lenient, which reads the messages before the cut.
TEST(Truncation, ACutBagSaysCutShortAndNamesLenient) {
  test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/odom", "nav_msgs/Odometry");
  for (std::uint32_t s = 1; s < 20; ++s) {
    b.message(1, s, 0, test::odom_message(s, 0, 0.1 * s, 0.0, 0.0));
    b.message(0, s, 0, test::scan_message(s, 0, "", std::vector<float>(30, 2.0F)));
  }
  const std::string bag = b.finish("none");
  const auto path = test::temp_dir() / "cut.bag";
  EXPECT_EQ(strict_error(path, bag), "");
  const std::string cut = strict_error(path, bag.substr(0, bag.size() / 2));
  EXPECT_NE(cut.find(path.string() + ": byte "), std::string::npos) << cut;
  EXPECT_NE(cut.find("lies past its end, at byte "), std::string::npos) << cut;
  EXPECT_NE(cut.find(": cut short? --lenient reads the scans before the cut)"), std::string::npos)
      << cut;
}

TEST(Corruption, FlippedBytesGiveInputErrorsOrData) {
  MOTE_REQUIRE_DATA(path, "wean/robotdata1.clf");
  const std::string log = test::read_bytes(path);
  const auto dir = test::temp_dir();
  std::mt19937_64 rng(42);
  int errors = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::string copy = log;
    for (int k = 0; k < 5; ++k) {
      copy[rng() % copy.size()] = static_cast<char>(rng() & 0xFFU);
    }
    errors += read_copy(dir / "flip.clf", copy, false).threw ? 1 : 0;
    const Outcome lenient = read_copy(dir / "flip.clf", copy, true);
    EXPECT_FALSE(lenient.threw);
    EXPECT_GE(lenient.frames + lenient.stats.records_skipped, 713U - 5U);
  }
  EXPECT_GT(errors, 0);
  test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/odom", "nav_msgs/Odometry");
  for (std::uint32_t s = 1; s < 20; ++s) {
    b.message(1, s, 0, test::odom_message(s, 0, 0.1 * s, 0.0, 0.0));
    b.message(0, s, 0, test::scan_message(s, 0, "", std::vector<float>(30, 2.0F)));
  }
  for (const char* kind : {"none", "bz2", "lz4"}) {
    const std::string bag = b.finish(kind);
    for (int trial = 0; trial < 200; ++trial) {
      std::string copy = bag;
      copy[rng() % copy.size()] = static_cast<char>(rng() & 0xFFU);
      (void)read_copy(dir / "flip.bag", copy, false);
      (void)read_copy(dir / "flip.bag", copy, true);
    }
  }
}

}  // namespace
}  // namespace mote::logs
