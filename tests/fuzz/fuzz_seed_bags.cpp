// Writes small ROS 1 bags as fuzzing seeds (tests/logs/bag_builder.hpp): every chunk
// compression, odometry from nav_msgs/Odometry and from tf. Usage: fuzz_seed_bags OUT_DIR.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "bag_builder.hpp"

namespace {

std::string odometry_bag(const std::string& compression) {
  mote::test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/odom", "nav_msgs/Odometry");
  for (std::uint32_t s = 1; s < 4; ++s) {
    b.message(1, s, 0, mote::test::odom_message(s, 0, 0.1 * s, 0.0, 0.05 * s));
    b.message(0, s, 5, mote::test::scan_message(s, 5, "laser", {1.0F, 2.0F, 3.0F}));
  }
  return b.finish(compression);
}

std::string tf_bag(const std::string& compression) {
  mote::test::BagBuilder b;
  b.connection(0, "/scan", "sensor_msgs/LaserScan");
  b.connection(1, "/tf", "tf2_msgs/TFMessage");
  for (std::uint32_t s = 1; s < 4; ++s) {
    b.message(1, s, 0, mote::test::tf_message(s, 0, "odom", "base_link", 0.2 * s, 0.0, 0.0));
    b.message(1, s, 0, mote::test::tf_message(s, 0, "base_link", "laser", 0.1, 0.0, 0.0));
    b.message(0, s, 5, mote::test::scan_message(s, 5, "laser", {1.5F, 2.5F}));
  }
  return b.finish(compression);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_seed_bags OUT_DIR\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  for (const char* kind : {"none", "bz2", "lz4"}) {
    std::ofstream(out / (std::string("odom_") + kind + ".bag"), std::ios::binary)
        << odometry_bag(kind);
    std::ofstream(out / (std::string("tf_") + kind + ".bag"), std::ios::binary) << tf_bag(kind);
  }
  return 0;
}
