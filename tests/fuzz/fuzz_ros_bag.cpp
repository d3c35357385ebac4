// libFuzzer target: ROS 1 bags, read whole in strict mode and again in lenient mode.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "mote/logs/scan_source.hpp"

namespace {

void read_bag(const std::filesystem::path& path, bool lenient) {
  mote::logs::ReaderOptions options;
  options.lenient = lenient;
  // The default 128 MiB chunk limit is checked by the tests; a smaller one keeps each run fast
  // (chunk buffers are allocated at their declared size before decompression).
  options.max_chunk_bytes = std::size_t{4} << 20U;
  auto source = mote::logs::open_ros_bag(path, options);
  while (source->next()) {
  }
  const mote::logs::ReadStats stats = source->stats();
  if (!lenient && stats.records_skipped != 0) mote::fuzz::finding("strict reader skipped records");
  if (stats.records_skipped > 0 && stats.first_error.empty()) {
    mote::fuzz::finding("records skipped without a first error");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path bag = mote::fuzz::write_input("log.bag", data, size);
  for (const bool lenient : {false, true}) {
    mote::fuzz::expect_clean(bag.string(), [&] { read_bag(bag, lenient); });
  }
  return 0;
}
