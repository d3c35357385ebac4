// Start-up on big maps: the tables a likelihood-field run builds before its first update, on
// Intel's map tiled n x n (and 12 x 9, the 9768 x 6840 floor of 67 M cells), beside the naive
// way it was built before (float distance field of a copy of the grid, then f per cell). Reports
// seconds and the bytes per cell the tables keep. Needs the shared data (skips without it).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include "mote/engine/executor.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/likelihood_table.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/maps/signed_distance_field.hpp"
#include "mote_bench/data.hpp"

namespace {

constexpr float kClamp = 2.0F;  // m: laser_likelihood_max_dist's default

/// Intel's map tiled nx across and ny up (null without the shared data); the last one is kept.
const mote::OccupancyGrid* tiled_intel(int nx, int ny) {
  static std::unique_ptr<mote::OccupancyGrid> tiled;
  static int kept_nx = 0;
  static int kept_ny = 0;
  if (tiled && kept_nx == nx && kept_ny == ny) return tiled.get();
  const auto path = mote::bench::data_dir() / "intel" / "intel.yaml";
  if (!std::filesystem::exists(path)) return nullptr;
  const mote::OccupancyGrid intel = mote::load_map(path);
  const auto w = static_cast<std::size_t>(intel.width());
  const auto h = static_cast<std::size_t>(intel.height());
  std::vector<mote::CellState> cells(w * h * static_cast<std::size_t>(nx * ny));
  const std::size_t row = w * static_cast<std::size_t>(nx);
  for (std::size_t j = 0; j < h * static_cast<std::size_t>(ny); ++j) {
    for (std::size_t t = 0; t < static_cast<std::size_t>(nx); ++t) {
      const auto* src = intel.cells().data() + (j % h) * w;
      std::copy(src, src + w, cells.begin() + static_cast<std::ptrdiff_t>(j * row + t * w));
    }
  }
  tiled.reset();
  tiled =
      std::make_unique<mote::OccupancyGrid>(intel.width() * nx, intel.height() * ny,
                                            intel.resolution(), intel.origin(), std::move(cells));
  kept_nx = nx;
  kept_ny = ny;
  return tiled.get();
}

float log_density(float d) {  // the product-mode table's shape (sigma_hit 0.2 m)
  return std::log(0.95F * std::exp(-d * d / 0.08F) + 0.05F / 40.0F);
}

/// The grid with only occupied cells that touch a free cell kept (the naive path's copy).
mote::OccupancyGrid surface_copy(const mote::OccupancyGrid& grid) {
  std::vector<mote::CellState> cells(grid.cells().size(), mote::CellState::kFree);
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      if (grid.at({i, j}) != mote::CellState::kOccupied) continue;
      for (const mote::CellIndex n : {mote::CellIndex{i - 1, j}, mote::CellIndex{i + 1, j},
                                      mote::CellIndex{i, j - 1}, mote::CellIndex{i, j + 1}}) {
        if (grid.at_or(n, mote::CellState::kOccupied) == mote::CellState::kFree) {
          cells[grid.linear_index({i, j})] = mote::CellState::kOccupied;
          break;
        }
      }
    }
  }
  return {grid.width(), grid.height(), grid.resolution(), grid.origin(), std::move(cells)};
}

/// Occupied and free swapped (the naive signed field's copy for the depth inside walls).
mote::OccupancyGrid inside_out(const mote::OccupancyGrid& grid) {
  std::vector<mote::CellState> cells = grid.cells();
  for (mote::CellState& c : cells) {
    if (c == mote::CellState::kOccupied) {
      c = mote::CellState::kFree;
    } else if (c == mote::CellState::kFree) {
      c = mote::CellState::kOccupied;
    }
  }
  return {grid.width(), grid.height(), grid.resolution(), grid.origin(), std::move(cells)};
}

void report(benchmark::State& state, const mote::OccupancyGrid& grid, double kept_bytes) {
  const auto cells = static_cast<double>(grid.cell_count());
  state.counters["Mcells"] = cells / 1e6;
  state.counters["bytes/cell"] = kept_bytes / cells;
  state.counters["cells/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * cells,
                                                 benchmark::Counter::kIsRate);
}

/// What a likelihood-field Localizer builds now: the table straight from the grid, and the
/// signed field (the scan matcher's and the ray walks') in 2 bytes per cell.
void BM_Maps_StartupTables(benchmark::State& state) {
  const mote::OccupancyGrid* grid =
      tiled_intel(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (grid == nullptr) return state.SkipWithError("no shared data (set MOTE_DATA_DIR)");
  const mote::Executor ex(static_cast<int>(state.range(2)));
  double kept = 0.0;
  for (auto _ : state) {
    ex([&] {
      const mote::LikelihoodTable table(*grid, mote::ObstacleCells::kSurface, kClamp, log_density,
                                        log_density(kClamp));
      const mote::SignedDistanceField field(*grid, kClamp);
      benchmark::DoNotOptimize(table.data());
      kept = 4.0 * static_cast<double>(table.stride()) * table.height() +
             2.0 * static_cast<double>(grid->cell_count());
    });
  }
  report(state, *grid, kept);
}

/// The naive baseline, as mote built them before: a float distance field of a surface copy of
/// the grid, f per cell into a table filled twice, and three more float transforms for the
/// obstacle distance and the signed field.
void BM_Maps_StartupTablesNaive(benchmark::State& state) {
  const mote::OccupancyGrid* grid =
      tiled_intel(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (grid == nullptr) return state.SkipWithError("no shared data (set MOTE_DATA_DIR)");
  const mote::Executor ex(static_cast<int>(state.range(2)));
  double kept = 0.0;
  for (auto _ : state) {
    ex([&] {
      const mote::DistanceField surface(surface_copy(*grid), {.max_distance = kClamp});
      const mote::LikelihoodTable table(surface, log_density, log_density(kClamp));
      const mote::DistanceField plain(*grid, {.max_distance = kClamp});
      const mote::DistanceField out(*grid, {.max_distance = kClamp + 0.025F});
      const mote::DistanceField in(inside_out(*grid),
                                   {.unknown_is_obstacle = true, .max_distance = kClamp});
      benchmark::DoNotOptimize(table.data());
      benchmark::DoNotOptimize(in.distances().data());
      kept = 4.0 * static_cast<double>(table.stride()) * table.height() +
             4.0 * 4.0 * static_cast<double>(grid->cell_count());
    });
  }
  report(state, *grid, kept);
}

void startup_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"nx", "ny", "threads"});
  for (const auto& [nx, ny] :
       {std::pair{1, 1}, std::pair{2, 2}, std::pair{5, 5}, std::pair{12, 9}}) {
    for (const int threads : {1, 2}) b->Args({nx, ny, threads});
  }
  b->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(3);
}
BENCHMARK(BM_Maps_StartupTables)->Apply(startup_args);
BENCHMARK(BM_Maps_StartupTablesNaive)->Apply(startup_args);

}  // namespace
