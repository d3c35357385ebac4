// libFuzzer target: MCAP files (a lone .mcap through the ROS 2 scan source), read whole in
// strict mode and again in lenient mode.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "mote/logs/scan_source.hpp"

namespace {

void read_mcap(const std::filesystem::path& path, bool lenient) {
  mote::logs::ReaderOptions options;
  options.lenient = lenient;
  options.max_chunk_bytes = std::size_t{4} << 20U;  // as fuzz_ros_bag: keeps each run fast
  auto source = mote::logs::open_ros2_bag(path, options);
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
  const std::filesystem::path file = mote::fuzz::write_input("log.mcap", data, size);
  for (const bool lenient : {false, true}) {
    mote::fuzz::expect_clean(file.string(), [&] { read_mcap(file, lenient); });
  }
  return 0;
}
