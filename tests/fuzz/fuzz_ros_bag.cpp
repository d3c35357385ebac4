// libFuzzer target: ROS 1 bags, read whole in strict mode and again in lenient mode
// (fuzz_scan_log.hpp).
#include <cstddef>
#include <cstdint>

#include "fuzz_scan_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return mote::fuzz::fuzz_scan_log("log.bag", &mote::logs::open_ros_bag, data, size);
}
