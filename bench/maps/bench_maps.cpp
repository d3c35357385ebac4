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

namespace {

namespace fs = std::filesystem;

/// A size x size office-like PGM: free floor inside an unknown margin, random walls and
/// rectangular rooms (0 = occupied, 254 = free, 205 = unknown), plus its map_server YAML.
fs::path write_map(int size) {
  const fs::path dir = fs::temp_directory_path() / ("mote_bench_maps_" + std::to_string(size));
  fs::create_directories(dir);
  const auto n = static_cast<std::size_t>(size);
  std::vector<unsigned char> px(n * n, 205);
  const std::size_t margin = n / 20;
  for (std::size_t r = margin; r < n - margin; ++r) {
    std::fill(px.begin() + static_cast<long>(r * n + margin),
              px.begin() + static_cast<long>(r * n + n - margin), 254);
  }
  std::mt19937 rng(42);
  std::uniform_int_distribution<std::size_t> pos(margin, n - margin - 1);
  auto wall = [&](std::size_t r0, std::size_t c0, std::size_t r1, std::size_t c1) {
    for (std::size_t r = r0; r <= std::min(r1, n - 1); ++r)
      for (std::size_t c = c0; c <= std::min(c1, n - 1); ++c) px[r * n + c] = 0;
  };
  for (int k = 0; k < size / 8; ++k) {
    const std::size_t r = pos(rng), c = pos(rng), len = pos(rng) / 8;
    if (k % 3 == 0) {  // a room outline
      wall(r, c, r + 1, c + len), wall(r + len, c, r + len + 1, c + len);
      wall(r, c, r + len, c + 1), wall(r, c + len, r + len + 1, c + len + 1);
    } else if (k % 3 == 1) {
      wall(r, c, r + 2, c + len);
    } else {
      wall(r, c, r + len, c + 2);
    }
  }
  std::ofstream(dir / "map.pgm", std::ios::binary) << "P5\n"
                                                   << size << ' ' << size << "\n255\n"
                                                   << std::string(px.begin(), px.end());
  std::ofstream(dir / "map.yaml")
      << "image: map.pgm\nresolution: 0.05\norigin: [-100.0, -100.0, 0.0]\n"
         "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  return dir / "map.yaml";
}

const fs::path& big_map() {
  static const fs::path yaml = write_map(4000);
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
