/// \file
/// Malformed bags: every defect gives an InputError naming the file and a byte offset, and
/// nothing is allocated from a declared length that the file cannot hold.

#include <gtest/gtest.h>

#include "bag_builder.hpp"
#include "mote/core/error.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote_test/log_files.hpp"

namespace mote::logs {
namespace {

using test::field;

std::string good_bag(const std::string& compression = "none") {
  test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/odom", "nav_msgs/Odometry");
  b.message(1, 1, 0, test::odom_message(1, 0, 0.0, 0.0, 0.0));
  b.message(0, 1, 0, test::scan_message(1, 0, "", {1.0F, 2.0F}));
  b.message(1, 2, 0, test::odom_message(2, 0, 1.0, 0.0, 0.0));
  return b.finish(compression);
}

/// Reads `bytes` as a bag and returns the InputError message (empty when none was thrown).
std::string error_of(const std::string& bytes, bool lenient = false) {
  const auto path = test::temp_dir() / "bad.bag";
  test::write_bytes(path, bytes);
  ReaderOptions options;
  options.lenient = lenient;
  try {
    auto source = open_ros_bag(path, options);
    (void)test::read_all(*source);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.place().rfind("byte ", 0), 0U) << e.what();
    return e.what();
  }
  return {};
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
}

TEST(BagBadInput, GoodBagReads) { EXPECT_EQ(error_of(good_bag()), ""); }

TEST(BagBadInput, BadMagic) {
  std::string bag = good_bag();
  bag[9] = '1';
  EXPECT_NE(error_of(bag).find("magic"), std::string::npos);
  EXPECT_NE(error_of("#ROS").find("magic"), std::string::npos);
}

TEST(BagBadInput, UnknownCompression) {
  std::string bag = good_bag();
  replace_all(bag, "compression=none", "compression=zip!");
  EXPECT_NE(error_of(bag).find("unknown chunk compression 'zip!'"), std::string::npos);
}

TEST(BagBadInput, HugeDeclaredLengthsAreNotAllocated) {
  std::string bag = good_bag();
  // The bag header's header length, then a chunk's declared uncompressed size.
  std::string huge = bag;
  huge.replace(13, 4, test::u32_bytes(0xFFFFFFF0U));
  EXPECT_NE(error_of(huge).find("only"), std::string::npos);
  std::string chunk_size = bag;
  const std::size_t at = chunk_size.find("size=") + 5;
  chunk_size.replace(at, 4, test::u32_bytes(0xFFFFFFF0U));
  EXPECT_NE(error_of(chunk_size).find("more than the limit"), std::string::npos);
  // A ranges array longer than its message.
  std::string ranges = bag;
  const std::string two = test::u32_bytes(2) + std::string("\x00\x00\x80\x3f", 4);
  ranges.replace(ranges.find(two), 4, test::u32_bytes(0x40000000U));
  EXPECT_NE(error_of(ranges).find("ranges length exceeds"), std::string::npos);
}

TEST(BagBadInput, CorruptCompressedChunks) {
  for (const char* kind : {"bz2", "lz4"}) {
    std::string bag = good_bag(kind);
    const std::size_t chunk = bag.find("compression=") + 40;
    bag[chunk] = static_cast<char>(bag[chunk] ^ 0x55);
    const std::string e = error_of(bag);
    EXPECT_NE(e.find("chunk"), std::string::npos) << kind << ": " << e;
  }
}

TEST(BagBadInput, NonFiniteOdometry) {
  test::BagBuilder b;
  b.connection(1, "/odom", "nav_msgs/Odometry");
  b.message(1, 1, 0, test::odom_message(1, 0, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0));
  EXPECT_NE(error_of(b.finish("none")).find("position.x: expected a finite number"),
            std::string::npos);
}

TEST(BagBadInput, MissingOpAndUnknownConnection) {
  std::string bag = good_bag();
  std::string no_op = bag;
  replace_all(no_op, "op=\x02", "xx=\x02");
  EXPECT_NE(error_of(no_op).find("lacks field 'op'"), std::string::npos);
  std::string unknown = bag;
  replace_all(unknown, std::string("op=\x02", 4) + "\x08", std::string("op=\x02", 4) + "\x08");
  test::BagBuilder b;
  b.message(9, 1, 0, "x");
  EXPECT_NE(error_of(b.finish("none")).find("unknown connection"), std::string::npos);
}

TEST(BagBadInput, ScansWithoutOdometry) {
  test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.message(0, 1, 0, test::scan_message(1, 0, "", {1.0F}));
  const auto path = test::temp_dir() / "no_odom.bag";
  test::write_bytes(path, b.finish("none"));
  auto source = open_ros_bag(path);
  EXPECT_THROW((void)test::read_all(*source), InputError);
}

TEST(BagBadInput, LenientModeSkipsABadMessageAndKeepsTheRest) {
  std::string bag = good_bag();
  const std::string two = test::u32_bytes(2) + std::string("\x00\x00\x80\x3f", 4);
  bag.replace(bag.find(two), 4, test::u32_bytes(4));  // ranges overrun their message
  EXPECT_NE(error_of(bag).find("ranges"), std::string::npos);
  const auto path = test::temp_dir() / "lenient.bag";
  test::write_bytes(path, bag);
  ReaderOptions options;
  options.lenient = true;
  auto source = open_ros_bag(path, options);
  EXPECT_TRUE(test::read_all(*source).empty());
  EXPECT_EQ(source->stats().records_skipped, 1U);
  EXPECT_EQ(source->stats().records_read, 2U);
  EXPECT_NE(source->stats().first_error.find("ranges"), std::string::npos);
}

}  // namespace
}  // namespace mote::logs
