// libFuzzer target: the nav_msgs/msg/OccupancyGrid decoder of the live node
// (ros/include/mote/ros/messages.hpp), fed the bytes of a DDS sample as they arrive on /map.
// It may only return a map or throw an InputError naming the topic and a byte offset, and a map
// it returns must survive encoding and decoding again unchanged.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "mote/ros/messages.hpp"

namespace {

namespace r = mote::ros;

// Far above what inputs of libFuzzer's length limit can fill, so the bound is exercised by the
// announced size alone (a grid's data must be in the message).
constexpr std::uint64_t kMaxCells = std::uint64_t{1} << 24U;

void round_trip(const r::MapMessage& map) {
  // A frame id with a NUL inside decodes (CDR counts bytes) but no CDR string can carry it.
  if (map.header.frame_id.find('\0') != std::string::npos) return;
  const r::MapMessage again =
      r::decode_occupancy_grid(r::encode_occupancy_grid(map.header, map.grid), "/map", kMaxCells);
  if (again.grid.cells() != map.grid.cells() || again.grid.width() != map.grid.width() ||
      again.grid.resolution() != map.grid.resolution() ||
      again.grid.origin().x != map.grid.origin().x ||
      again.header.frame_id != map.header.frame_id) {
    mote::fuzz::finding("an OccupancyGrid changed on encoding and decoding again");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  mote::fuzz::expect_clean("/map",
                           [&] { round_trip(r::decode_occupancy_grid(bytes, "/map", kMaxCells)); });
  return 0;
}
