// The distance transform against the brute-force baseline on a small map, and likelihood-table
// lookups against a double-precision world_to_cell walk with a bounds branch.
#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "mote/engine/executor.hpp"
#include "mote/maps/likelihood_table.hpp"

namespace {

mote::OccupancyGrid small_grid(int size) {
  std::mt19937 rng(5);
  std::bernoulli_distribution wall(0.02);
  std::vector<mote::CellState> cells(static_cast<std::size_t>(size) *
                                     static_cast<std::size_t>(size));
  for (auto& c : cells) c = wall(rng) ? mote::CellState::kOccupied : mote::CellState::kFree;
  return {size, size, 0.05, mote::Pose2{-5.0, -5.0, 0.3}, std::move(cells)};
}

void BM_Maps_DistanceFieldSmall(benchmark::State& state) {
  const mote::Executor ex(1);
  const mote::OccupancyGrid grid = small_grid(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    ex([&] { benchmark::DoNotOptimize(mote::DistanceField(grid).distances().data()); });
  }
  state.counters["cells/s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * grid.cell_count()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Maps_DistanceFieldSmall)->Arg(200)->UseRealTime()->Unit(benchmark::kMicrosecond);

/// Naive baseline: every cell against every obstacle cell.
void BM_Maps_DistanceBruteForce(benchmark::State& state) {
  const mote::OccupancyGrid grid = small_grid(static_cast<int>(state.range(0)));
  std::vector<mote::CellIndex> obstacles;
  for (int j = 0; j < grid.height(); ++j)
    for (int i = 0; i < grid.width(); ++i)
      if (grid.at({i, j}) == mote::CellState::kOccupied) obstacles.push_back({i, j});
  std::vector<float> out(grid.cell_count());
  for (auto _ : state) {
    for (int j = 0; j < grid.height(); ++j) {
      for (int i = 0; i < grid.width(); ++i) {
        int best = std::numeric_limits<int>::max();
        for (const auto& o : obstacles)
          best = std::min(best, (i - o.i) * (i - o.i) + (j - o.j) * (j - o.j));
        out[grid.linear_index({i, j})] = static_cast<float>(std::sqrt(best) * grid.resolution());
      }
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["cells/s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * grid.cell_count()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Maps_DistanceBruteForce)->Arg(200)->UseRealTime()->Unit(benchmark::kMicrosecond);

struct LookupFixture {
  mote::OccupancyGrid grid = small_grid(1000);
  mote::DistanceField field{grid};
  mote::LikelihoodTable table{field, [](float d) { return -d * d; }, -100.0F};
  std::vector<float> xs, ys;
  mutable std::vector<float> out = std::vector<float>(1 << 16);
  LookupFixture() {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-60.0F, 60.0F);
    for (int k = 0; k < 1 << 16; ++k) xs.push_back(u(rng)), ys.push_back(u(rng));
  }
};

void BM_Maps_TableLookup(benchmark::State& state) {
  static const LookupFixture fx;
  const mote::LikelihoodView view = fx.table.view();  // a local copy, as a hot loop would
  const float* xs = fx.xs.data();
  const float* ys = fx.ys.data();
  float* out = fx.out.data();
  for (auto _ : state) {
    for (std::size_t k = 0; k < fx.xs.size(); ++k) out[k] = view.lookup(xs[k], ys[k]);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.counters["lookups/s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * fx.xs.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Maps_TableLookup);

/// Baseline: double-precision world_to_cell and a bounds branch per point, as amcl does.
void BM_Maps_GridLookupBranchy(benchmark::State& state) {
  static const LookupFixture fx;
  float* out = fx.out.data();
  for (auto _ : state) {
    for (std::size_t k = 0; k < fx.xs.size(); ++k) {
      const mote::CellIndex c = fx.grid.world_to_cell({fx.xs[k], fx.ys[k]});
      out[k] = fx.grid.contains(c) ? -fx.field.at(c) * fx.field.at(c) : -100.0F;
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.counters["lookups/s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * fx.xs.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Maps_GridLookupBranchy);

}  // namespace
