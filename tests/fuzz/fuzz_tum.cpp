// libFuzzer target: TUM trajectories, read from memory through the stream overload.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_support.hpp"
#include "mote/logs/tum.hpp"

namespace {

void read(const std::string& text) {
  std::istringstream in(text);
  for (const mote::logs::StampedPose& p : mote::logs::read_tum(in, "fuzz.tum")) {
    if (!std::isfinite(p.stamp) || !std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) ||
        !std::isfinite(p.pose.theta)) {
      mote::fuzz::finding("read_tum returned a non-finite pose");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mote::fuzz::expect_clean("fuzz.tum", [&] { read(text); });
  return 0;
}
