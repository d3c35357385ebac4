// libFuzzer target: the CDR decoders (logs/src/ros2_messages.hpp). The first byte picks the
// message type, the rest is the serialized message; a decoder may only return or throw
// BagDecodeError with an offset inside the message.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "bag_format.hpp"
#include "fuzz_support.hpp"
#include "ros2_messages.hpp"

namespace {

namespace d = mote::logs::detail;

void decode(std::uint8_t type, std::string_view bytes) {
  switch (type % 4U) {
    case 0:
      (void)d::decode_laser_scan_cdr(bytes);
      break;
    case 1:
      (void)d::decode_odometry_cdr(bytes);
      break;
    case 2:
      (void)d::decode_tf_cdr(bytes);
      break;
    default:
      (void)d::decode_pose_cdr(bytes);
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    decode(data[0], bytes);
  } catch (const d::BagDecodeError& e) {
    if (e.offset > bytes.size()) mote::fuzz::finding("decode error offset past the message");
    if (e.problem.empty()) mote::fuzz::finding("decode error without a problem");
  }
  (void)d::schema_mismatch(static_cast<d::Ros2Type>(1 + data[0] % 4U), bytes);
  return 0;
}
