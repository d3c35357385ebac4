#pragma once
/// \file
/// Locating ../shared/data from benchmarks (a benchmark whose data is absent reports
/// SkipWithError).

#include <cstdlib>
#include <filesystem>

namespace mote::bench {

/// The data folder: $MOTE_DATA_DIR, else the path configured at build time.
inline std::filesystem::path data_dir() {
  if (const char* env = std::getenv("MOTE_DATA_DIR"); env != nullptr && *env != '\0') return env;
  return MOTE_BENCH_DATA_DIR;
}

}  // namespace mote::bench
