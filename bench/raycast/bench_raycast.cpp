// Rays per second for the Embree caster (16-ray packets and single rays) and the range table
// against the exact grid walk, on the Intel and Willow maps, for tracking-like and global
// particle sets, on 1 and 2 threads; and the range table's build time on Intel and on a
// generated 4000 x 4000 map. Run: build/bench/raycast/bench_raycast
// Arguments of every case: map (0 Intel, 1 Willow), particles (0 tracking, 1 global), threads.

#include <benchmark/benchmark.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "mote/maps/map_loader.hpp"
#include "mote/raycast/grid_ray_caster.hpp"
#include "mote/raycast/range_table.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote_bench/data.hpp"
#include "mote_bench/office_map.hpp"

namespace {

constexpr std::size_t kParticles = 2000;
constexpr int kBeams = 60;
constexpr float kMaxRange = 30.0F;

const char* map_path(int map) {
  return map == 0 ? "intel/intel.yaml" : "maps/willow-full-0.05.yaml";
}

/// Particle columns and beam angles for one scenario: tracking (a 0.3 m, 0.2 rad cloud around
/// one free pose: coherent rays) or global (uniform over free space: incoherent rays).
struct Workload {
  std::vector<float> x, y, theta, beams;
  std::vector<float> ranges;

  Workload(const mote::OccupancyGrid& grid, bool global) {
    const double spread = 0.3;
    const double turn = 0.2;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<> u(0.0, 1.0);
    std::normal_distribution<> n(0.0, 1.0);
    const auto& free = grid.free_cells();
    const auto pick = [&] {
      return static_cast<std::size_t>(u(rng) * static_cast<double>(free.size())) % free.size();
    };
    const mote::Point2 centre = grid.free_point(pick(), 0.5, 0.5);
    for (std::size_t i = 0; i < kParticles; ++i) {
      const mote::Point2 p =
          global ? grid.free_point(pick(), u(rng), u(rng))
                 : mote::Point2{centre.x + spread * n(rng), centre.y + spread * n(rng)};
      x.push_back(static_cast<float>(p.x));
      y.push_back(static_cast<float>(p.y));
      theta.push_back(
          static_cast<float>(global ? (u(rng) * 2.0 - 1.0) * std::numbers::pi : turn * n(rng)));
    }
    for (int b = 0; b < kBeams; ++b) {
      beams.push_back(static_cast<float>(-std::numbers::pi + 2.0 * std::numbers::pi * b / kBeams));
    }
    ranges.resize(x.size() * beams.size());
  }
  [[nodiscard]] mote::RayBatch batch() const {
    return {x, y, theta, beams, mote::Pose2{0.1, 0.0, 0.0}, kMaxRange};
  }
};

/// Maps load once per process.
const mote::OccupancyGrid* grid_for(int map) {
  static std::map<int, std::unique_ptr<mote::OccupancyGrid>> cache;
  auto& slot = cache[map];
  if (!slot) {
    const auto path = mote::bench::data_dir() / map_path(map);
    if (!std::filesystem::exists(path)) return nullptr;
    slot = std::make_unique<mote::OccupancyGrid>(mote::load_map(path));
  }
  return slot.get();
}

/// The 4000 x 4000 map of 5 cm cells that bench_maps uses: unknown border, free interior,
/// random rooms and walls.
mote::OccupancyGrid big_grid() { return mote::load_map(mote::bench::write_office_map(4000)); }

/// The range table of a map, built once per process (default options: 512 angles, 256 MB).
const mote::RangeTable* table_for(int map) {
  static std::map<int, std::unique_ptr<mote::RangeTable>> cache;
  auto& slot = cache[map];
  if (!slot) {
    const mote::OccupancyGrid* grid = grid_for(map);
    if (grid == nullptr) return nullptr;
    slot = std::make_unique<mote::RangeTable>(*grid);
  }
  return slot.get();
}

/// The range table, built once per map outside the timed loop.
struct TableCaster {
  const mote::RangeTable* table;
  TableCaster(const mote::OccupancyGrid& grid, const mote::RayCastOptions&) {
    for (int map : {0, 1}) {
      if (grid_for(map) == &grid) table = table_for(map);
    }
  }
  void cast(const mote::RayBatch& batch, std::span<float> ranges) const {
    table->cast(batch, ranges);
  }
};

template <class Caster>
void run_cast(benchmark::State& state, const mote::RayCastOptions& options) {
  const mote::OccupancyGrid* grid = grid_for(static_cast<int>(state.range(0)));
  if (grid == nullptr) {
    state.SkipWithError("recorded map not found (set MOTE_DATA_DIR)");
    return;
  }
  const Caster caster(*grid, options);
  Workload work(*grid, state.range(1) != 0);
  const mote::RayBatch batch = work.batch();
  tbb::task_arena arena(static_cast<int>(state.range(2)));
  for (auto _ : state) {
    arena.execute([&] { caster.cast(batch, work.ranges); });
    benchmark::DoNotOptimize(work.ranges.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(work.ranges.size()));
  const char* kinds[] = {" tracking", " global"};
  state.SetLabel(std::string(state.range(0) == 0 ? "intel" : "willow") + kinds[state.range(1)]);
}

void BM_RayCast_Embree16(benchmark::State& state) {
  run_cast<mote::RayCaster>(state, mote::RayCastOptions{});
}

void BM_RayCast_Embree1(benchmark::State& state) {
  mote::RayCastOptions options;
  options.packets = false;
  run_cast<mote::RayCaster>(state, options);
}

/// The baseline: the exact grid walk (test oracle).
void BM_RayCast_GridWalk(benchmark::State& state) {
  run_cast<mote::GridRayCaster>(state, mote::RayCastOptions{});
}

void BM_RayCast_Table(benchmark::State& state) {
  run_cast<TableCaster>(state, mote::RayCastOptions{});
}

/// Table build time with the default options (512 angles, 256 MB budget): map 0 Intel (every
/// cell), 1 Willow and 2 the generated 4000 x 4000 map, both over budget on every cell, so on a
/// coarser lattice. Counters: the table's size and layout, and (untimed, after the builds) its
/// accuracy against Embree on 20000 rays from free cells up to 30 m, which on a coarse lattice
/// is not what test_range_table measures on every cell.
void BM_RangeTable_Build(benchmark::State& state) {
  const int map = static_cast<int>(state.range(0));
  static const mote::OccupancyGrid big = big_grid();
  const mote::OccupancyGrid* grid = map == 2 ? &big : grid_for(map);
  if (grid == nullptr) {
    state.SkipWithError("recorded map not found (set MOTE_DATA_DIR)");
    return;
  }
  tbb::task_arena arena(static_cast<int>(state.range(1)));
  std::unique_ptr<mote::RangeTable> table;
  for (auto _ : state) {
    table.reset();
    arena.execute([&] { table = std::make_unique<mote::RangeTable>(*grid); });
  }
  const mote::RangeTableStats& stats = table->stats();
  const mote::RayCaster exact(*grid);
  mote::RangeTableAccuracy acc;
  arena.execute([&] { acc = mote::measure_range_table(*table, exact, *grid, 20000, 30.0F); });
  state.counters["within_1_cell"] = acc.within_one_cell;
  state.counters["within_2_cells"] = acc.within_two_cells;
  state.counters["MB"] = static_cast<double>(stats.bytes) / 1048576.0;
  state.counters["lattice"] = stats.lattice;
  state.counters["angles"] = stats.angles;
  state.SetLabel(map == 0 ? "intel" : map == 1 ? "willow" : "4000x4000");
}

/// A fixed compute loop on 1 and 2 threads: how many cores the machine gave right now
/// (design.md section 4: the second core comes and goes). Compare the two rates.
void BM_Machine_ComputeLoop(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  tbb::task_arena arena(threads);
  constexpr int kTasks = 64;
  std::vector<double> sink(kTasks);
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(/*first=*/0, /*last=*/kTasks, /*body=*/[&](int t) {
        double v = t;
        for (int k = 0; k < 200000; ++k) v = v * 1.0000001 + 1e-9;
        sink[static_cast<std::size_t>(t)] = v;
      });
    });
    benchmark::DoNotOptimize(sink.data());
  }
  state.SetItemsProcessed(state.iterations() * kTasks * 200000);
}

void cases(benchmark::internal::Benchmark* b) {
  b->ArgNames({"map", "global", "threads"});
  for (const int map : {0, 1}) {
    for (const int global : {0, 1}) {
      for (const int threads : {1, 2}) b->Args({map, global, threads});
    }
  }
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(BM_Machine_ComputeLoop)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RayCast_Embree16)->Apply(cases);
BENCHMARK(BM_RayCast_Embree1)->Apply(cases);
BENCHMARK(BM_RayCast_GridWalk)->Apply(cases);
BENCHMARK(BM_RayCast_Table)->Apply(cases);
BENCHMARK(BM_RangeTable_Build)
    ->ArgNames({"map", "threads"})
    ->Args({0, 2})
    ->Args({1, 2})
    ->Args({2, 2})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Machine_ComputeLoop)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
