// libFuzzer target: MCAP files (a lone .mcap through the ROS 2 scan source), read whole in
// strict mode and again in lenient mode (fuzz_scan_log.hpp).
#include <cstddef>
#include <cstdint>

#include "fuzz_scan_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return mote::fuzz::fuzz_scan_log("log.mcap", &mote::logs::open_ros2_bag, data, size);
}
