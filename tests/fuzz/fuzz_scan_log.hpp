#pragma once
/// \file
/// The harness the scan-log fuzz targets share (CARMEN, ROS 1 bags, MCAP): the input written to
/// a file named as a log of its format, read whole in strict mode and again in lenient mode.
/// Besides fuzz_support.hpp's checks, a strict read must not skip records and a lenient one
/// must say why it skipped any.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "fuzz_support.hpp"
#include "mote/logs/scan_source.hpp"

namespace mote::fuzz {

/// One of mote::logs' openers: open_carmen_log, open_ros_bag, open_ros2_bag.
using OpenLog = std::unique_ptr<logs::ScanSource> (*)(const std::filesystem::path&,
                                                      const logs::ReaderOptions&);

inline void read_log(OpenLog open, const std::filesystem::path& path, bool lenient) {
  logs::ReaderOptions options;
  options.lenient = lenient;
  // The default 128 MiB chunk limit is checked by the tests; a smaller one keeps each run fast
  // (bag chunk buffers are allocated at their declared size before decompression). CARMEN logs
  // have no chunks.
  options.max_chunk_bytes = std::size_t{4} << 20U;
  auto source = open(path, options);
  while (source->next()) {
  }
  const logs::ReadStats stats = source->stats();
  if (!lenient && stats.records_skipped != 0) finding("strict reader skipped records");
  if (stats.records_skipped > 0 && stats.first_error.empty()) {
    finding("records skipped without a first error");
  }
}

/// The body of LLVMFuzzerTestOneInput for a scan-log reader; `file_name` gives the extension.
inline int fuzz_scan_log(const char* file_name, OpenLog open, const std::uint8_t* data,
                         std::size_t size) {
  const std::filesystem::path file = write_input(file_name, data, size);
  for (const bool lenient : {false, true}) {
    expect_clean(file.string(), [&] { read_log(open, file, lenient); });
  }
  return 0;
}

}  // namespace mote::fuzz
