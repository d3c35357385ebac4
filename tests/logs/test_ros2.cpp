/// \file
/// ROS 2 logs end to end through open_scan_log: MCAP in every layout (chunked or not, none/zstd/
/// lz4, with or without summary), CRCs, truncation at every byte, rosbag2 sqlite3 files and
/// folders, topic choice, odometry from tf, and the laser mount (an upside-down laser mirrors).

#include <gtest/gtest.h>
#include <unistd.h>

#include <numbers>

#include "mote/core/error.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote_test/log_files.hpp"
#include "ros2_builder.hpp"

namespace mote::logs {
namespace {

namespace r2 = mote::test::ros2;
using std::numbers::pi;

/// Scans at t = 1..4 s on /scan, odometry every 0.5 s moving along x, the laser 0.2 m ahead of
/// base_link turned +90 degrees (or upside down) on /tf_static.
r2::McapBuilder recording(bool upside_down = false) {
  r2::McapBuilder b;
  b.channel(1, "/tf_static", "tf2_msgs/msg/TFMessage");
  b.channel(2, "/scan", "sensor_msgs/msg/LaserScan");
  b.channel(3, "/odom", "nav_msgs/msg/Odometry");
  b.message(1, 0.5, r2::tf_message(0.5, {{"base_link", "laser", 0.2, 0.0, pi / 2, upside_down}}));
  for (int k = 1; k <= 9; ++k) {
    const double t = 0.5 * k;
    b.message(3, t, r2::odometry(t, 0.1 * k, 0.0, 0.0, k % 2 == 0));
    if (k % 2 == 0) b.message(2, t + 0.01, r2::laser_scan(t + 0.01, "laser", {1.0F, 2.0F, NAN}));
  }
  return b;
}

std::vector<ScanFrame> read_file(const std::filesystem::path& path,
                                 const ReaderOptions& options = {}, ReadStats* stats = nullptr) {
  auto source = open_scan_log(path, options);
  std::vector<ScanFrame> frames = test::read_all(*source);
  if (stats != nullptr) *stats = source->stats();
  return frames;
}

std::vector<ScanFrame> read_mcap(const std::string& bytes, ReadStats* stats = nullptr) {
  const auto path = test::temp_dir() / "log.mcap";
  test::write_bytes(path, bytes);
  return read_file(path, {}, stats);
}

/// The InputError message reading `bytes` as an MCAP file gives; "" when it reads.
std::string mcap_error(const std::string& bytes) {
  try {
    (void)read_mcap(bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_same(const std::vector<ScanFrame>& a, const std::vector<ScanFrame>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].stamp, b[k].stamp);
    EXPECT_EQ(a[k].odometry, b[k].odometry);
    EXPECT_EQ(a[k].scan.angle_min, b[k].scan.angle_min);
    EXPECT_EQ(a[k].scan.sensor_pose, b[k].scan.sensor_pose);
    EXPECT_EQ(a[k].scan.ranges.size(), b[k].scan.ranges.size());
  }
}

TEST(Ros2Mcap, EveryLayoutAndCompressionReadsTheSameFrames) {
  const std::vector<ScanFrame> reference = read_mcap(recording().finish());
  ASSERT_EQ(reference.size(), 4U);
  EXPECT_NEAR(reference[0].stamp, 1.01, 1e-9);
  EXPECT_NEAR(reference[0].odometry.x, 0.2 + 0.01 / 0.5 * 0.1, 1e-9);  // interpolated
  EXPECT_NEAR(reference[0].scan.sensor_pose.x, 0.2, 1e-12);
  EXPECT_NEAR(reference[0].scan.sensor_pose.theta, pi / 2, 1e-12);
  for (const char* compression : {"", "zstd", "lz4"}) {
    for (const bool chunked : {true, false}) {
      for (const bool summary : {true, false}) {
        for (const bool crcs : {true, false}) {
          r2::McapBuilder b = recording();
          b.compression = compression;
          b.chunked = chunked;
          b.summary = summary;
          b.crcs = crcs;
          ReadStats stats;
          SCOPED_TRACE(std::string(compression) + (chunked ? " chunked" : " unchunked") +
                       (summary ? " summary" : "") + (crcs ? " crc" : ""));
          expect_same(read_mcap(b.finish(), &stats), reference);
          EXPECT_TRUE(stats.warnings.empty());
        }
      }
    }
  }
}

TEST(Ros2Mcap, AnUpsideDownLaserMirrorsItsBeamAngles) {
  const std::vector<ScanFrame> frames = read_mcap(recording(true).finish());
  ASSERT_FALSE(frames.empty());
  // Beam angle a in the laser frame is pi/2 - a in the base frame: angle_min -1 -> +1, and the
  // increment 0.5 -> -0.5 around a mount heading of pi/2.
  EXPECT_FLOAT_EQ(frames[0].scan.angle_min, 1.0F);
  EXPECT_FLOAT_EQ(frames[0].scan.angle_increment, -0.5F);
  EXPECT_NEAR(frames[0].scan.sensor_pose.theta, pi / 2, 1e-12);
}

TEST(Ros2Mcap, WrongCrcsAreErrors) {
  r2::McapBuilder b = recording();
  b.summary = false;
  const std::string good = b.finish();
  // A range value inside the first chunk (uncompressed, so the byte is the CRC's input).
  std::string chunk_flip = good;
  const std::size_t scan_at = good.find("laser");
  chunk_flip[scan_at + 20] = static_cast<char>(chunk_flip[scan_at + 20] ^ 1);
  EXPECT_NE(mcap_error(chunk_flip).find("(chunk), offset"), std::string::npos)
      << mcap_error(chunk_flip);
  EXPECT_NE(mcap_error(chunk_flip).find("chunk CRC mismatch"), std::string::npos);
  // The header's library name is covered only by the Data End record's CRC.
  std::string header_flip = good;
  header_flip[good.find("mote test")] = 'M';
  EXPECT_NE(mcap_error(header_flip).find("data section CRC mismatch"), std::string::npos);
  // The summary CRC.
  const std::string indexed = recording().finish();
  std::string summary_flip = indexed;
  summary_flip[indexed.rfind("/odom")] = '_';
  EXPECT_NE(mcap_error(summary_flip).find("summary CRC mismatch"), std::string::npos);
}

TEST(Ros2Mcap, ALengthThatClaimsGigabytesIsRefusedBeforeAllocating) {
  r2::McapBuilder b = recording();
  b.summary = false;
  std::string bad = b.finish();
  // The first chunk's uncompressed_size (after opcode, length and two times) claims 1 TB.
  const std::size_t chunk = 8 + 9 + static_cast<unsigned char>(bad[9]);  // after the header
  ASSERT_EQ(bad[chunk], '\x06');
  std::string size;
  r2::put_le(size, std::uint64_t{1} << 40U, 8);
  bad.replace(chunk + 9 + 16, 8, size);
  EXPECT_NE(mcap_error(bad).find("more than the limit"), std::string::npos) << mcap_error(bad);
}

TEST(Ros2Mcap, SchemaTextThatDoesNotMatchItsTypeIsAnError) {
  r2::McapBuilder b = recording();
  b.schema_override["sensor_msgs/msg/LaserScan"] = "std_msgs/Header header\nfloat64 angle_min\n";
  const std::string e = mcap_error(b.finish());
  EXPECT_NE(e.find("channel id 2, schema id 2: schema text of sensor_msgs/msg/LaserScan does not "
                   "match it: field 2 is 'float64 angle_min'"),
            std::string::npos)
      << e;
}

TEST(Ros2Mcap, ACdrStringPastItsMessageNamesFileChunkAndOffset) {
  r2::McapBuilder b = recording();
  b.compression = "zstd";
  std::string scan = r2::laser_scan(1.01, "laser", {1.0F});
  scan[12] = '\x7f';  // frame_id length
  b.messages[3].data = scan;
  const std::string e = mcap_error(b.finish());
  EXPECT_NE(e.find("log.mcap: byte "), std::string::npos) << e;
  EXPECT_NE(e.find("(message record), byte 12 of the message: /scan (sensor_msgs/msg/LaserScan): "
                   "header.frame_id: string of"),
            std::string::npos)
      << e;
}

/// A file cut short while recording (no summary, no footer) replays up to its last complete
/// record with a warning; every cut either does that or is a one-line InputError.
TEST(Ros2Mcap, TruncationAtEveryByte) {
  for (const char* compression : {"", "zstd"}) {
    r2::McapBuilder b = recording();
    b.compression = compression;
    b.summary = false;
    const std::string full = b.finish();
    const std::vector<ScanFrame> all = read_mcap(full);
    // Thousands of small rewrites: tmpfs when there is one (a disk's truncating opens are slow).
    const std::filesystem::path shm = "/dev/shm";
    const auto path = (std::filesystem::is_directory(shm) ? shm : test::temp_dir()) /
                      ("mote_cut_" + std::to_string(::getpid()) + ".mcap");
    int replayed = 0;
    for (std::size_t cut = 0; cut < full.size(); ++cut) {
      test::write_bytes(path, full.substr(0, cut));
      try {
        ReadStats stats;
        const std::vector<ScanFrame> frames = read_file(path, {}, &stats);
        ASSERT_LE(frames.size(), all.size()) << cut;
        for (std::size_t k = 0; k < frames.size(); ++k) EXPECT_EQ(frames[k].stamp, all[k].stamp);
        EXPECT_EQ(stats.warnings.size(), 1U) << "cut at " << cut;
        ++replayed;
      } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path.string());
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      }
    }
    std::filesystem::remove(path);
    EXPECT_GT(replayed, static_cast<int>(full.size() / 3)) << compression;
  }
}

TEST(Ros2Sqlite, Db3FilesAndFoldersOfSeveralFilesRead) {
  const r2::McapBuilder rec = recording();
  const std::vector<ScanFrame> reference = read_mcap(rec.finish());  // before temp_dir() below
  std::vector<std::tuple<int, double, std::string>> first;
  std::vector<std::tuple<int, double, std::string>> second;
  for (const auto& m : rec.messages) {
    auto& part = m.time < 2'600'000'000ULL ? first : second;
    part.emplace_back(m.channel - 1, static_cast<double>(m.time) * 1e-9, m.data);
  }
  const std::vector<std::pair<std::string, std::string>> topics{
      {"/tf_static", "tf2_msgs/msg/TFMessage"},
      {"/scan", "sensor_msgs/msg/LaserScan"},
      {"/odom", "nav_msgs/msg/Odometry"}};
  const auto dir = test::temp_dir();
  const auto bag = dir / "bag";
  std::filesystem::create_directories(bag);
  r2::write_db3(bag / "bag_0.db3", topics, first);
  r2::write_db3(bag / "bag_1.db3", topics, second);
  test::write_bytes(bag / "metadata.yaml",
                    "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
                    "  relative_file_paths:\n    - bag_0.db3\n    - bag_1.db3\n");
  expect_same(read_file(bag), reference);
  auto all = first;
  all.insert(all.end(), second.begin(), second.end());
  r2::write_db3(dir / "one.db3", topics, all);
  expect_same(read_file(dir / "one.db3"), reference);
}

TEST(Ros2Topics, SeveralScanTopicsAreAnErrorListingThemUnlessOneIsChosen) {
  r2::McapBuilder b = recording();
  b.channel(4, "/scan_rear", "sensor_msgs/msg/LaserScan");
  const std::string e = mcap_error(b.finish());
  EXPECT_NE(e.find("several sensor_msgs/msg/LaserScan topics: '/scan', '/scan_rear'; choose one "
                   "with --scan-topic"),
            std::string::npos)
      << e;
  const auto path = test::temp_dir() / "two.mcap";
  test::write_bytes(path, b.finish());
  ReaderOptions chosen;
  chosen.scan_topic = "/scan";
  EXPECT_EQ(read_file(path, chosen).size(), 4U);
  chosen.scan_topic = "/nope";
  EXPECT_THROW((void)read_file(path, chosen), InputError);
}

TEST(Ros2Topics, OdometryFromTfWhenThereIsNoOdometryTopic) {
  r2::McapBuilder b;
  b.channel(1, "/tf", "tf2_msgs/msg/TFMessage");
  b.channel(2, "/scan", "sensor_msgs/msg/LaserScan");
  for (int k = 1; k <= 6; ++k) {
    const double t = 0.5 * k;
    b.message(1, t, r2::tf_message(t, {{"odom", "base_link", 0.1 * k, 0.0, 0.0, false}}));
    if (k % 2 == 0) b.message(2, t, r2::laser_scan(t, "base_link", {1.0F}));
  }
  const auto path = test::temp_dir() / "tf.mcap";
  test::write_bytes(path, b.finish());
  const std::vector<ScanFrame> frames = read_file(path);
  ASSERT_EQ(frames.size(), 3U);
  EXPECT_NEAR(frames[1].odometry.x, 0.4, 1e-12);
  // A second child of odom on tf makes the base frame ambiguous unless --base-frame names it.
  r2::McapBuilder two = b;
  two.message(1, 3.2, r2::tf_message(3.2, {{"odom", "base_footprint", 0.6, 0.0, 0.0, false}}));
  const auto path2 = path.parent_path() / "two_bases.mcap";
  test::write_bytes(path2, two.finish());
  try {
    (void)read_file(path2);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("several frames under 'odom' on tf: 'base_footprint', "
                                         "'base_link'; choose one with --base-frame"),
              std::string::npos)
        << e.what();
  }
  ReaderOptions base;
  base.base_frame = "base_link";
  EXPECT_EQ(read_file(path2, base).size(), 3U);
  ReaderOptions wrong;
  wrong.odom_frame = "world";
  try {
    (void)read_file(path, wrong);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("parent frames on tf: 'odom'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mote::logs
