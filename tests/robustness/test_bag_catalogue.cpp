// Bad-input catalogue for ROS 1 bags, strict and lenient, built in memory with the log tests'
// bag builder and cut from the recorded DIS bag.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "bag_builder.hpp"
#include "catalogue.hpp"
#include "log_cases.hpp"
#include "mote_test/data.hpp"

namespace mote::robustness {
namespace {

namespace tb = mote::test;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// sensor_msgs/LaserScan with chosen limits (angle_min, angle_increment, range_min, range_max).
std::string scan(float angle_min, float increment, float range_min, float range_max,
                 std::uint32_t declared_ranges = 2, const std::string& tail = "") {
  std::string m;
  tb::put_u32(m, 0);
  tb::put_time(m, 1, 0);
  tb::put_string(m, "laser");
  for (float v : {angle_min, 1.0F, increment, 0.0F, 0.1F, range_min, range_max}) tb::put_f32(m, v);
  tb::put_u32(m, declared_ranges);
  tb::put_f32(m, 1.0F);
  tb::put_f32(m, 2.0F);
  tb::put_u32(m, 0);
  return m + tail;
}

std::string good_scan() { return scan(-1.0F, 1.0F, 0.05F, 10.0F); }

/// A bag with odometry around one scan message `scan_bytes` (and `odom` for the first pose).
std::string bag_around(const std::string& scan_bytes, const std::string& compression = "none",
                       const std::string& odom = tb::odom_message(1, 0, 0.0, 0.0, 0.0)) {
  tb::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/odom", "nav_msgs/Odometry");
  b.message(1, 1, 0, odom);
  b.message(0, 1, 0, scan_bytes);
  b.message(1, 2, 0, tb::odom_message(2, 0, 1.0, 0.0, 0.0));
  return b.finish(compression);
}

std::string tf_bag(const std::string& tf) {
  tb::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/tf", "tf2_msgs/TFMessage");
  b.message(1, 1, 0, tf);
  b.message(0, 1, 0, good_scan());
  b.message(1, 2, 0, tb::tf_message(2, 0, "odom", "laser", 1.0, 0.0, 0.0));
  return b.finish("none");
}

std::string replaced(std::string bytes, const std::string& from, const std::string& to) {
  const std::size_t at = bytes.find(from);
  EXPECT_NE(at, std::string::npos) << "builder layout changed";
  return at == std::string::npos ? bytes : bytes.replace(at, from.size(), to);
}

/// The chunk's declared uncompressed size replaced by `size`.
std::string chunk_size(const std::string& bag, std::uint32_t size) {
  const std::size_t at = bag.find("size=") + 5;
  return bag.substr(0, at) + tb::u32_bytes(size) + bag.substr(at + 4);
}

/// A byte of the compressed chunk body flipped (its first byte: the bz2 or LZ4 magic).
std::string chunk_body_flipped(const std::string& bag) {
  std::string out = bag;
  const std::size_t size_field = out.find("size=") + 9;  // end of the chunk header
  const std::size_t body = size_field + 4;               // after the data length
  out[body] = static_cast<char>(out[body] ^ 0x5A);
  return out;
}

/// Offsets where the top-level records start (after the 13-byte magic).
std::vector<std::size_t> record_starts(const std::string& bag) {
  const auto u32 = [&bag](std::size_t k) {
    std::uint32_t v = 0;
    for (std::size_t i = 4; i-- > 0;) v = (v << 8U) | static_cast<unsigned char>(bag[k + i]);
    return static_cast<std::size_t>(v);
  };
  std::vector<std::size_t> starts;
  for (std::size_t at = 13; at + 4 <= bag.size();) {
    starts.push_back(at);
    const std::size_t data_at = at + 4 + u32(at);
    at = data_at + 4 + u32(data_at);
  }
  return starts;
}

/// Only a cut at a record start at or past the index position (the end of the builder's one
/// chunk, the third record) leaves a complete bag.
Expect bag_cut(const std::string& bag, std::size_t cut) {
  const std::vector<std::size_t> starts = record_starts(bag);
  const std::size_t index_pos = starts.size() > 2 ? starts[2] : bag.size();
  const bool boundary = std::find(starts.begin(), starts.end(), cut) != starts.end();
  return boundary && cut >= index_pos ? Expect::kErrorOrValid : Expect::kError;
}

/// The magic and bag header record of `bag`, then `record` in place of the chunk.
std::string header_then(const std::string& bag, const std::string& record) {
  return bag.substr(0, record_starts(bag).at(1)) + record;
}

/// The bag header's index position moved to 2^40, far past the end of the file.
std::string index_past_end(std::string bag) {
  std::string far;
  tb::put_u64(far, std::uint64_t{1} << 40U);
  return bag.replace(bag.find("index_pos=") + 10, 8, far);
}

std::vector<Case> bag_cases() {
  const std::string good = bag_around(good_scan());
  std::string huge_string = good_scan();
  huge_string.replace(12, 4, tb::u32_bytes(0xFFFFFFFFU));  // frame_id length
  std::string many_transforms = tb::tf_message(1, 0, "odom", "base", 0, 0, 0);
  many_transforms.replace(0, 4, tb::u32_bytes(0x10000000U));
  tb::BagBuilder no_odom;
  no_odom.connection(0, "/scan", "sensor_msgs/LaserScan");
  no_odom.message(0, 1, 0, good_scan());
  tb::BagBuilder no_scan;
  no_scan.connection(1, "/odom", "nav_msgs/Odometry");
  no_scan.message(1, 1, 0, tb::odom_message(1, 0, 0.0, 0.0, 0.0));
  tb::BagBuilder unknown_conn;
  unknown_conn.message(9, 1, 0, good_scan());
  std::vector<Case> cases{
      {"empty", ""},
      {"magic only", "#ROSBAG V2.0\n"},
      {"magic of version 1.2", "#ROSBAG V1.2\n" + good.substr(13)},
      {"magic without newline", "#ROSBAG V2.0" + good.substr(13)},
      {"a CARMEN log", "FLASER 3 1 2 3 0 0 0 0 0 0 1 host 1\n"},
      {"random bytes", random_bytes(4096, 21)},
      {"magic then random bytes", "#ROSBAG V2.0\n" + random_bytes(4096, 22)},
      {"header length 2^32-16", good.substr(0, 13) + tb::u32_bytes(0xFFFFFFF0U) + good.substr(17)},
      {"chunk size 2^32-16", chunk_size(good, 0xFFFFFFF0U)},
      {"chunk size 256 MiB", chunk_size(good, 256U << 20U)},
      {"chunk size too small", chunk_size(good, 10)},
      {"bz2 chunk size 64 MiB", chunk_size(bag_around(good_scan(), "bz2"), 64U << 20U)},
      {"lz4 chunk size 64 MiB", chunk_size(bag_around(good_scan(), "lz4"), 64U << 20U)},
      {"index past the end", index_past_end(good)},
      {"ranges length 2^30", bag_around(scan(-1.0F, 1.0F, 0.05F, 10.0F, 0x40000000U))},
      {"frame_id length 2^32-1", bag_around(huge_string)},
      {"transforms length 2^28", tf_bag(many_transforms)},
      {"LaserScan trailing bytes", bag_around(scan(-1.0F, 1.0F, 0.05F, 10.0F, 2, "xx"))},
      {"LaserScan cut", bag_around(good_scan().substr(0, 30))},
      {"angle_min NaN", bag_around(scan(static_cast<float>(kNaN), 1.0F, 0.05F, 10.0F))},
      {"angle_increment inf", bag_around(scan(-1.0F, static_cast<float>(kInf), 0.05F, 10.0F))},
      {"range_min NaN", bag_around(scan(-1.0F, 1.0F, static_cast<float>(kNaN), 10.0F))},
      {"range_max NaN", bag_around(scan(-1.0F, 1.0F, 0.05F, static_cast<float>(kNaN)))},
      {"range_max zero", bag_around(scan(-1.0F, 1.0F, 0.05F, 0.0F))},
      {"odometry x NaN", bag_around(good_scan(), "none", tb::odom_message(1, 0, kNaN, 0, 0))},
      {"odometry y inf", bag_around(good_scan(), "none", tb::odom_message(1, 0, 0, kInf, 0))},
      {"odometry yaw inf", bag_around(good_scan(), "none", tb::odom_message(1, 0, 0, 0, kInf))},
      {"odometry cut",
       bag_around(good_scan(), "none", tb::odom_message(1, 0, 0, 0, 0).substr(0, 99))},
      {"odometry trailing bytes",
       bag_around(good_scan(), "none", tb::odom_message(1, 0, 0, 0, 0) + "x")},
      {"tf x NaN", tf_bag(tb::tf_message(1, 0, "odom", "laser", kNaN, 0, 0))},
      {"tf zero quaternion", tf_bag(replaced(tb::tf_message(1, 0, "odom", "laser", 0, 0, 0),
                                             tb::u32_bytes(0) + tb::u32_bytes(0x3ff00000U),
                                             tb::u32_bytes(0) + tb::u32_bytes(0)))},
      {"header field without '='", replaced(good, "compression=none", "compression:none")},
      {"op of two bytes", header_then(good, tb::record(tb::field("op", "\x07\x07"), "x"))},
      {"conn of three bytes",
       header_then(good, tb::record(tb::field("op", "\x07") + tb::field("conn", "abc") +
                                        tb::field("topic", "/scan"),
                                    tb::field("type", "sensor_msgs/LaserScan")))},
      {"record data length past the end",
       header_then(good, tb::u32_bytes(8) + tb::field("op", "\x07") + tb::u32_bytes(0x7FFFFFFFU))},
      {"missing op", replaced(good, "op=\x02", "xx=\x02")},
      {"unknown compression", replaced(good, "compression=none", "compression=zip!")},
      {"compression with a newline", replaced(good, "compression=none", "compression=\nnon")},
      {"bz2 magic flipped", chunk_body_flipped(bag_around(good_scan(), "bz2"))},
      {"lz4 magic flipped", chunk_body_flipped(bag_around(good_scan(), "lz4"))},
      {"message on an unknown connection", unknown_conn.finish("none")},
      {"scans without odometry", no_odom.finish("none")},
      {"odometry without scans", no_scan.finish("lz4")},
  };
  for (const char* kind : {"none", "bz2", "lz4"}) {
    const std::string bag = bag_around(good_scan(), kind);
    const auto expect = [&bag](std::size_t cut) { return bag_cut(bag, cut); };
    for (Case& c : truncations(std::string(kind) + " bag", bag, expect)) {
      cases.push_back(std::move(c));
    }
    for (Case& c : byte_flips(std::string(kind) + " bag", bag, 80, 1, 23)) {
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

TEST(BagCatalogue, Cases) {
  const fs::path dir = scratch("bag");
  const std::vector<Case> cases = bag_cases();
  EXPECT_GT(run_log_cases(cases, dir / "log.bag"), static_cast<int>(cases.size() / 2));
}

TEST(BagCatalogue, RecordedBagCut) {
  MOTE_REQUIRE_DATA(path, "dis/dis-underground.bag");
  const fs::path dir = scratch("bag_recorded");
  const std::string bag = read_file(path).substr(0, std::size_t{2} << 20U);
  // Every cut of the first 2 MiB loses the index and most chunks: strict mode must say so.
  const std::vector<Case> cases = truncations(
      "DIS bag", bag, [](std::size_t) { return Expect::kError; }, 16);
  EXPECT_EQ(run_log_cases(cases, dir / "log.bag"), static_cast<int>(cases.size()));
}

}  // namespace
}  // namespace mote::robustness
