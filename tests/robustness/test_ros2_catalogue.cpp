// Bad-input catalogue for ROS 2 logs: MCAP files (framing, chunks, CRCs, summary, schemas),
// CDR messages inside them, rosbag2 sqlite3 files and metadata.yaml, strict and lenient.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "catalogue.hpp"
#include "log_cases.hpp"
#include "mote_test/data.hpp"
#include "ros2_builder.hpp"

namespace mote::robustness {
namespace {

namespace r2 = mote::test::ros2;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// /scan, /odom and /tf_static around one scan message `scan`.
r2::McapBuilder around(const std::string& scan, const std::string& compression = "",
                       const std::string& odom = r2::odometry(1.0, 0.0, 0.0, 0.0)) {
  r2::McapBuilder b;
  b.compression = compression;
  b.channel(1, "/tf_static", "tf2_msgs/msg/TFMessage");
  b.channel(2, "/scan", "sensor_msgs/msg/LaserScan");
  b.channel(3, "/odom", "nav_msgs/msg/Odometry");
  b.message(1, 0.5, r2::tf_message(0.5, {{"base_link", "laser", 0.1, 0.0, 0.0, false}}));
  b.message(3, 1.0, odom);
  b.message(2, 1.5, scan);
  b.message(3, 2.0, r2::odometry(2.0, 1.0, 0.0, 0.0));
  return b;
}

std::string good_scan() { return r2::laser_scan(1.5, "laser", {1.0F, 2.0F}); }

std::string mcap(const r2::McapBuilder& b) { return b.finish(); }

std::string no_summary(r2::McapBuilder b) {
  b.summary = false;
  return b.finish();
}

/// The first chunk's record offset: after the magic and the header record.
std::size_t first_chunk(const std::string& file) {
  return 8 + 9 + static_cast<unsigned char>(file[9]);
}

std::string patched_u64(std::string file, std::size_t at, std::uint64_t v) {
  std::string bytes;
  r2::put_le(bytes, v, 8);
  return file.replace(at, 8, bytes);
}

std::string flipped(std::string file, std::size_t at) {
  file[at] = static_cast<char>(file[at] ^ 0x41);
  return file;
}

std::string with_bytes(std::string message, std::size_t at, const std::string& bytes) {
  return message.replace(at, bytes.size(), bytes);
}

std::vector<Case> mcap_cases() {
  const std::string good = mcap(around(good_scan()));
  const std::string linear = no_summary(around(good_scan()));
  const std::size_t chunk = first_chunk(good);
  const std::size_t footer = good.size() - 8 - 29;
  r2::McapBuilder wrong_schema = around(good_scan());
  wrong_schema.schema_override["sensor_msgs/msg/LaserScan"] =
      r2::schema_text("nav_msgs/msg/Odometry");
  r2::McapBuilder imu = around(good_scan());
  imu.channels[2].second = "sensor_msgs/msg/Imu";  // no scan topic left
  r2::McapBuilder no_odom = around(good_scan());
  no_odom.channels.erase(3);
  no_odom.messages.erase(no_odom.messages.begin() + 3);
  no_odom.messages.erase(no_odom.messages.begin() + 1);
  r2::McapBuilder brotli = around(good_scan());
  brotli.compression = "brotli";  // the builder stores the records as they are
  const std::string scan = good_scan();
  std::vector<Case> cases{
      {"empty", ""},
      {"magic only", std::string(r2::kMcapMagic, 8)},
      {"magic cut", std::string(r2::kMcapMagic, 5)},
      {"random bytes", random_bytes(4096, 31)},
      {"magic then random bytes", std::string(r2::kMcapMagic, 8) + random_bytes(4096, 32)},
      {"a ROS 1 bag", "#ROSBAG V2.0\n" + random_bytes(64, 33)},
      {"chunk uncompressed_size 2^40", patched_u64(linear, chunk + 9 + 16, 1ULL << 40U)},
      {"chunk uncompressed_size 256 MiB", patched_u64(linear, chunk + 9 + 16, 256ULL << 20U)},
      {"chunk uncompressed_size too small", patched_u64(good, chunk + 9 + 16, 10)},
      {"chunk record length 2^62 (indexed)", patched_u64(good, chunk + 1, 1ULL << 62U)},
      {"chunk record length 2^62 (linear)", patched_u64(linear, chunk + 1, 1ULL << 62U),
       Expect::kErrorOrValid},
      {"summary_start past the end", patched_u64(good, footer + 9, 1ULL << 40U)},
      {"summary_start inside the magic", patched_u64(good, footer + 9, 3)},
      {"unknown chunk compression", mcap(brotli)},
      {"chunk CRC wrong", flipped(good, chunk + 9 + 24)},
      {"chunk records flipped", flipped(linear, linear.find("base_link"))},
      {"summary CRC wrong", flipped(good, good.size() - 8 - 1)},
      {"summary flipped", flipped(good, good.rfind("/scan"))},
      {"data section CRC wrong", flipped(linear, linear.find("mote test"))},
      {"schema text of another type", mcap(wrong_schema)},
      {"no LaserScan topic", mcap(imu)},
      {"scans without odometry", mcap(no_odom)},
      {"LaserScan frame_id length 2^32-1",
       mcap(around(with_bytes(scan, 12, std::string(4, '\xff'))))},
      {"LaserScan ranges length 2^30",
       mcap(around(with_bytes(scan, 4 + 8 + 12 + 28, std::string("\x00\x00\x00\x40", 4))))},
      {"LaserScan cut", mcap(around(scan.substr(0, 30)))},
      {"LaserScan trailing bytes", mcap(around(scan + "trailing"))},
      {"LaserScan big-endian header, little-endian body",
       mcap(around(with_bytes(scan, 1, std::string(1, '\0'))))},
      {"CDR parameter list", mcap(around(with_bytes(scan, 1, "\x03")))},
      {"encapsulation only", mcap(around(scan.substr(0, 4)))},
      {"odometry x NaN", mcap(around(scan, "", r2::odometry(1.0, kNaN, 0.0, 0.0)))},
      {"odometry cut", mcap(around(scan, "", r2::odometry(1.0, 0, 0, 0).substr(0, 100)))},
      {"transforms length 2^28",
       [&] {
         r2::McapBuilder b = around(scan);
         b.messages[0].data = with_bytes(b.messages[0].data, 4, std::string("\0\0\0\x10", 4));
         return mcap(b);
       }()},
      {"tf zero quaternion",
       [&] {
         r2::McapBuilder b = around(scan);
         r2::CdrWriter w;
         w.u32(1).header(0.5, "base_link").string("laser");
         for (int k = 0; k < 7; ++k) w.f64(0.0);
         b.messages[0].data = w.bytes();
         return mcap(b);
       }()},
  };
  for (const char* compression : {"", "zstd", "lz4"}) {
    const std::string label = std::string("MCAP ") + (*compression ? compression : "none");
    const std::string file = mcap(around(good_scan(), compression));
    // A cut file replays up to its last complete record with a warning, or is an error.
    // Every byte for the uncompressed file, 150 cuts spread over the compressed ones.
    const std::size_t cuts = *compression ? 150 : 0;
    const auto expect = [](std::size_t) { return Expect::kErrorOrValid; };
    for (Case& c : truncations(label, file, expect, cuts)) {
      cases.push_back(std::move(c));
    }
    for (Case& c : byte_flips(label, file, 80, 1, 34)) cases.push_back(std::move(c));
  }
  return cases;
}

TEST(Ros2Catalogue, McapCases) {
  const fs::path dir = scratch("mcap");
  const std::vector<Case> cases = mcap_cases();
  EXPECT_GT(run_log_cases(cases, dir / "log.mcap"), 60);
}

TEST(Ros2Catalogue, Db3Cases) {
  const fs::path dir = scratch("db3");
  r2::write_db3(dir / "good.db3",
                {{"/scan", "sensor_msgs/msg/LaserScan"}, {"/odom", "nav_msgs/msg/Odometry"}},
                {{1, 1.0, r2::odometry(1.0, 0, 0, 0)},
                 {0, 1.5, good_scan()},
                 {1, 2.0, r2::odometry(2.0, 1, 0, 0)},
                 {0, 2.5, r2::laser_scan(2.5, "laser", {1.0F}).substr(0, 20)}});
  const std::string db = read_file(dir / "good.db3");
  std::vector<Case> cases{
      {"empty", ""},
      {"random bytes", random_bytes(8192, 41)},
      {"sqlite magic then random bytes", db.substr(0, 100) + random_bytes(8192, 42)},
      {"a cut scan message", db},
  };
  for (Case& c : truncations(
           "db3", db, [](std::size_t) { return Expect::kError; }, 40)) {
    cases.push_back(std::move(c));
  }
  for (Case& c : byte_flips("db3", db, 60, 4, 43)) cases.push_back(std::move(c));
  EXPECT_GT(run_log_cases(cases, dir / "log.db3"), 40);
}

TEST(Ros2Catalogue, Rosbag2MetadataCases) {
  const fs::path dir = scratch("rosbag2");
  const fs::path bag = dir / "bag";
  fs::create_directories(bag);
  const std::string head = "rosbag2_bagfile_information:\n  storage_identifier: sqlite3\n";
  const std::vector<Case> cases{
      {"empty", ""},
      {"not YAML", "rosbag2_bagfile_information: [\n"},
      {"a list", "- 1\n- 2\n"},
      {"no rosbag2_bagfile_information", "version: 5\n"},
      {"no relative_file_paths", head},
      {"relative_file_paths a string", head + "  relative_file_paths: a.db3\n"},
      {"relative_file_paths empty", head + "  relative_file_paths: []\n"},
      {"missing storage file", head + "  relative_file_paths: [missing.db3]\n"},
      {"storage identifier unknown",
       "rosbag2_bagfile_information:\n  storage_identifier: leveldb\n  relative_file_paths: "
       "[a]\n"},
      {"storage identifier a map",
       "rosbag2_bagfile_information:\n  storage_identifier: {a: 1}\n  relative_file_paths: "
       "[a]\n"},
      {"compressed bag", head + "  relative_file_paths: [a.db3]\n  compression_format: zstd\n"
                                "  compression_mode: FILE\n"},
      {"random bytes", random_bytes(512, 51)},
  };
  const auto read = [&bag](const fs::path&) { read_log(bag, false); };
  EXPECT_EQ(run_cases(cases, bag / "metadata.yaml", read), static_cast<int>(cases.size()));
}

TEST(Ros2Catalogue, RecordedMcapCut) {
  MOTE_REQUIRE_DATA(path, "ros2/mac_take2_zstd.mcap");
  const fs::path dir = scratch("mcap_recorded");
  const std::string file = read_file(path);
  const std::vector<Case> cases = truncations(
      "zstd MCAP", file, [](std::size_t) { return Expect::kErrorOrValid; }, 24);
  run_log_cases(cases, dir / "log.mcap");
}

}  // namespace
}  // namespace mote::robustness
