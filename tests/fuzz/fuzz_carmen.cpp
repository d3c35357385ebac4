// libFuzzer target: CARMEN logs, read whole in strict mode and again in lenient mode
// (fuzz_scan_log.hpp).
#include <cstddef>
#include <cstdint>

#include "fuzz_scan_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return mote::fuzz::fuzz_scan_log("log.clf", &mote::logs::open_carmen_log, data, size);
}
