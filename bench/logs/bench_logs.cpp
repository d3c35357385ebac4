// Reading and decoding the ROS 2 recording (issue 16): every scan frame of the zstd MCAP file,
// the lz4 and uncompressed MCAP files and the rosbag2 sqlite3 folder, in MB/s of file and
// scans/s, beside the naive baseline of reading the file's bytes and nothing else.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "mote/logs/scan_source.hpp"
#include "mote_bench/data.hpp"

namespace {

namespace fs = std::filesystem;

/// The bytes of a log: the file, or every file of a folder.
double log_bytes(const fs::path& path) {
  if (!fs::is_directory(path)) return static_cast<double>(fs::file_size(path));
  double total = 0.0;
  for (const auto& e : fs::directory_iterator(path)) {
    total += static_cast<double>(fs::file_size(e.path()));
  }
  return total;
}

void report(benchmark::State& state, double bytes, double scans) {
  const auto it = static_cast<double>(state.iterations());
  state.counters["MB/s"] = benchmark::Counter(it * bytes / 1e6, benchmark::Counter::kIsRate);
  state.counters["scans/s"] = benchmark::Counter(it * scans, benchmark::Counter::kIsRate);
}

void BM_Logs_ReadRos2(benchmark::State& state, const char* rel) {
  const fs::path path = mote::bench::data_dir() / rel;
  if (!fs::exists(path)) {
    state.SkipWithError(("recorded data not found: " + path.string()).c_str());
    return;
  }
  std::size_t scans = 0;
  for (auto _ : state) {
    scans = 0;
    auto source = mote::logs::open_scan_log(path);
    while (auto frame = source->next()) {
      benchmark::DoNotOptimize(frame->scan.ranges.data());
      ++scans;
    }
  }
  report(state, log_bytes(path), static_cast<double>(scans));
}
BENCHMARK_CAPTURE(BM_Logs_ReadRos2, mcap_zstd, "ros2/mac_take2_zstd.mcap")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Logs_ReadRos2, mcap_lz4, "ros2/mac_take2_lz4.mcap")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Logs_ReadRos2, mcap_none, "ros2/mac_take2_uncompressed.mcap")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Logs_ReadRos2, sqlite3_folder, "ros2/mac_take2")
    ->Unit(benchmark::kMillisecond);

/// Naive baseline: the file's bytes read into memory, nothing decoded.
void BM_Logs_ReadBytes(benchmark::State& state, const char* rel) {
  const fs::path path = mote::bench::data_dir() / rel;
  if (!fs::exists(path)) {
    state.SkipWithError(("recorded data not found: " + path.string()).c_str());
    return;
  }
  std::vector<char> buffer(std::size_t{1} << 20U);
  for (auto _ : state) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    while (std::fread(buffer.data(), 1, buffer.size(), f) == buffer.size()) {
    }
    std::fclose(f);
    benchmark::DoNotOptimize(buffer.data());
  }
  report(state, log_bytes(path), 0.0);
}
BENCHMARK_CAPTURE(BM_Logs_ReadBytes, mcap_zstd, "ros2/mac_take2_zstd.mcap")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Logs_ReadBytes, sqlite3_db3, "ros2/mac_take2/macfirst_floor_take_2_0.db3")
    ->Unit(benchmark::kMillisecond);

}  // namespace
