// Writes ROS 2 fuzzing seeds (tests/logs/ros2_builder.hpp): MCAP files in every layout and
// chunk compression into OUT/mcap, CDR messages (first byte: the type fuzz_cdr decodes) into
// OUT/cdr and metadata.yaml texts into OUT/rosbag2_metadata. Usage: fuzz_seed_ros2 OUT_DIR.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "ros2_builder.hpp"

namespace {

namespace r2 = mote::test::ros2;

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

r2::McapBuilder recording() {
  r2::McapBuilder b;
  b.channel(1, "/tf_static", "tf2_msgs/msg/TFMessage");
  b.channel(2, "/scan", "sensor_msgs/msg/LaserScan");
  b.channel(3, "/odom", "nav_msgs/msg/Odometry");
  b.message(1, 0.5, r2::tf_message(0.5, {{"base_link", "laser", 0.2, 0.0, 1.57, false}}));
  for (int k = 1; k <= 5; ++k) {
    b.message(3, 0.5 * k, r2::odometry(0.5 * k, 0.1 * k, 0.0, 0.0, k % 2 == 0));
    b.message(2, 0.5 * k + 0.1, r2::laser_scan(0.5 * k + 0.1, "laser", {1.0F, 2.0F, NAN}));
  }
  return b;
}

void mcap_seeds(const std::filesystem::path& dir) {
  for (const char* compression : {"", "zstd", "lz4"}) {
    for (const bool summary : {true, false}) {
      for (const bool chunked : {true, false}) {
        r2::McapBuilder b = recording();
        b.compression = compression;
        b.summary = summary;
        b.chunked = chunked;
        write(dir / (std::string("rec_") + (*compression ? compression : "none") +
                     (summary ? "_summary" : "") + (chunked ? "_chunked" : "") + ".mcap"),
              b.finish());
      }
    }
  }
}

void cdr_seeds(const std::filesystem::path& dir) {
  for (const bool little : {true, false}) {
    const std::string order = little ? "le" : "be";
    write(dir / ("scan_" + order), '\0' + r2::laser_scan(1.0, "laser", {1.0F, 2.0F}, little));
    write(dir / ("odom_" + order), '\1' + r2::odometry(1.0, 1.0, 2.0, 0.5, little));
    write(dir / ("tf_" + order),
          '\2' + r2::tf_message(1.0,
                                {{"odom", "base_link", 1.0, 0.0, 0.3, false},
                                 {"base_link", "laser", 0.1, 0.0, 3.1, true}},
                                little));
  }
}

void metadata_seeds(const std::filesystem::path& dir) {
  write(dir / "two_files.yaml",
        "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
        "  relative_file_paths:\n    - bag_0.db3\n    - bag_1.db3\n  compression_format: \"\"\n"
        "  compression_mode: \"\"\n");
  write(dir / "mcap.yaml",
        "rosbag2_bagfile_information:\n  storage_identifier: mcap\n  relative_file_paths: "
        "[bag_0.mcap]\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_seed_ros2 OUT_DIR\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  for (const char* sub : {"mcap", "cdr", "rosbag2_metadata"}) {
    std::filesystem::create_directories(out / sub);
  }
  mcap_seeds(out / "mcap");
  cdr_seeds(out / "cdr");
  metadata_seeds(out / "rosbag2_metadata");
  return 0;
}
