// libFuzzer target: map images (PGM/PPM P2, P3, P5, P6 and PNG, chosen by magic bytes), then
// classification into a grid in each map_server mode.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "mote/maps/map_loader.hpp"

namespace {

/// Classification reads every pixel; beyond this many the fuzzer would only measure memset.
constexpr long long kMaxClassifiedPixels = 1 << 22;

void classify(const mote::MapImage& image, const std::string& name) {
  if (static_cast<long long>(image.width) * image.height > kMaxClassifiedPixels) return;
  mote::MapMetadata meta;
  meta.resolution = 0.05;
  for (const mote::MapMode mode :
       {mote::MapMode::kTrinary, mote::MapMode::kScale, mote::MapMode::kRaw}) {
    meta.mode = mode;
    meta.negate = !meta.negate;
    const mote::OccupancyGrid grid = mote::grid_from_image(image, meta, name);
    if (grid.width() != image.width || grid.height() != image.height) {
      mote::fuzz::finding("grid size differs from the image size");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = mote::fuzz::write_input("map.img", data, size);
  const std::string name = file.string();
  mote::fuzz::expect_clean(name, [&] { classify(mote::read_map_image(file), name); });
  return 0;
}
