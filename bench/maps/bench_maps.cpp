// Map loading, the distance transform and likelihood lookups, each beside a serial or naive
// baseline. The 4000 x 4000 map is generated once into a temporary folder.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "mote/core/parallel.hpp"
#include "mote/engine/executor.hpp"
#include "mote/maps/likelihood_table.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_bench/office_map.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path& big_map() {
  static const fs::path yaml = mote::bench::write_office_map(4000);
  return yaml;
}

void set_cells_rate(benchmark::State& state, const mote::OccupancyGrid& grid) {
  state.counters["cells/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(grid.cell_count()),
      benchmark::Counter::kIsRate);
}

/// A fixed compute loop (no memory traffic) to see how many cores the machine gives right now
/// (design.md section 4: the second core comes and goes); quote 2-thread figures beside it.
void BM_Maps_CoreCheck(benchmark::State& state) {
  const mote::Executor ex(static_cast<int>(state.range(0)));
  constexpr std::size_t kItems = 1 << 12;
  std::vector<float> out(kItems);
  for (auto _ : state) {
    ex([&] {
      mote::par::for_each_chunk(kItems, /*grain=*/64, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
          float x = static_cast<float>(i);
          for (int k = 0; k < 20000; ++k) x = x * 0.999999F + 1e-3F;
          out[i] = x;
        }
      });
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["items/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * kItems,
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Maps_CoreCheck)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_Maps_LoadAndDistance(benchmark::State& state) {
  const mote::Executor ex(static_cast<int>(state.range(0)));
  const mote::OccupancyGrid grid = mote::load_map(big_map());
  for (auto _ : state) {
    ex([&] {
      const mote::OccupancyGrid g = mote::load_map(big_map());
      const mote::DistanceField field(g);
      benchmark::DoNotOptimize(field.distances().data());
    });
  }
  set_cells_rate(state, grid);
}
BENCHMARK(BM_Maps_LoadAndDistance)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_Maps_Load(benchmark::State& state) {
  const mote::Executor ex(static_cast<int>(state.range(0)));
  const mote::OccupancyGrid grid = mote::load_map(big_map());
  for (auto _ : state) {
    ex([&] { benchmark::DoNotOptimize(mote::load_map(big_map()).cells().data()); });
  }
  set_cells_rate(state, grid);
}
BENCHMARK(BM_Maps_Load)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_Maps_DistanceField(benchmark::State& state) {
  const mote::Executor ex(static_cast<int>(state.range(0)));
  const mote::OccupancyGrid grid = mote::load_map(big_map());
  for (auto _ : state) {
    ex([&] { benchmark::DoNotOptimize(mote::DistanceField(grid).distances().data()); });
  }
  set_cells_rate(state, grid);
}
BENCHMARK(BM_Maps_DistanceField)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
