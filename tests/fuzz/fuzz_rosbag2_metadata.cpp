// libFuzzer target: rosbag2 metadata.yaml through its parser (logs/src/rosbag2_metadata.cpp);
// the storage files it lists are fuzzed by fuzz_mcap (and sqlite3 is fuzzed upstream).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "ros2_storage.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string name = "metadata.yaml";
  mote::fuzz::expect_clean(name,
                           [&] { (void)mote::logs::detail::parse_rosbag2_metadata(text, name); });
  return 0;
}
