// libFuzzer target: CARMEN logs, read whole in strict mode and again in lenient mode.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "mote/logs/scan_source.hpp"

namespace {

void read_log(const std::filesystem::path& path, bool lenient) {
  mote::logs::ReaderOptions options;
  options.lenient = lenient;
  auto source = mote::logs::open_carmen_log(path, options);
  std::size_t frames = 0;
  while (source->next()) ++frames;
  const mote::logs::ReadStats stats = source->stats();
  if (!lenient && stats.records_skipped != 0) mote::fuzz::finding("strict reader skipped records");
  if (stats.records_skipped > 0 && stats.first_error.empty()) {
    mote::fuzz::finding("records skipped without a first error");
  }
  (void)frames;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path log = mote::fuzz::write_input("log.clf", data, size);
  for (const bool lenient : {false, true}) {
    mote::fuzz::expect_clean(log.string(), [&] { read_log(log, lenient); });
  }
  return 0;
}
