// libFuzzer target: map_server YAML metadata (read_map_metadata; the image is not opened).
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "mote/maps/map_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path yaml = mote::fuzz::write_input("map.yaml", data, size);
  mote::fuzz::expect_clean(yaml.string(), [&] { (void)mote::read_map_metadata(yaml); });
  return 0;
}
