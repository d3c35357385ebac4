// Normalization (log-sum-exp over the deterministic tree, ESS) against a naive serial pass
// with std::exp in double; KLD bin counting against a serial hash set of bin keys; and the beam
// model's likelihood over cast ranges (batched, vectorized) against the scalar double loop.

#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <unordered_set>
#include <vector>

#include "bench_engine_util.hpp"
#include "mote/engine/beam_model.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/weights.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote_bench/data.hpp"

namespace mote::bench {
namespace {

void BM_Weights_Normalize(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  ParticleStore store = random_store(n);
  const Executor ex(static_cast<int>(state.range(1)));
  ex([&] {
    for (auto _ : state) {
      // Normalized weights stay normalized: each iteration does the full work (max, sum,
      // subtract, ESS) on the same values up to rounding.
      benchmark::DoNotOptimize(normalize(store.view()));
    }
  });
  set_particle_rate(state, n);
}

void BM_Weights_NormalizeNaive(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  ParticleStore store = random_store(n);
  const ParticleView p = store.view();
  for (auto _ : state) {
    double max = -INFINITY;
    for (std::size_t i = 0; i < n; ++i) max = std::max(max, double{p.logw[i]});
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += std::exp(p.logw[i] - max);
    const double shift = max + std::log(sum);
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      p.logw[i] = static_cast<float>(p.logw[i] - shift);
      sum_sq += std::exp(2.0 * p.logw[i]);
    }
    benchmark::DoNotOptimize(sum_sq);
  }
  set_particle_rate(state, n);
}

// Counts the bins of n random particles in a 40 m square, in the bins of `region`.
void count_bins(benchmark::State& state, const Bounds2& region) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ParticleStore store = random_store(n);
  KldBins bins(region, 0.5, 0.5, 10.0 * 3.14159265 / 180);
  const Executor ex(static_cast<int>(state.range(1)));
  const KldConfig config;
  ex([&] {
    for (auto _ : state) benchmark::DoNotOptimize(kld_sample_count(store.view(), bins, config));
  });
  set_particle_rate(state, n);
}

void BM_Kld_CountBins(benchmark::State& state) { count_bins(state, {-20.0, -20.0, 20.0, 20.0}); }

// The same particles in the bins of a 490 m x 345 m map (the Intel map tiled 12 x 9): the
// count's cost follows the particles, not the map's area.
void BM_Kld_CountBinsBigMap(benchmark::State& state) {
  count_bins(state, {-20.0, -25.0, 470.0, 320.0});
}

void BM_Kld_CountBinsHashSet(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ParticleStore store = random_store(n);
  const KldBins bins({-20.0, -20.0, 20.0, 20.0}, 0.5, 0.5, 10.0 * 3.14159265 / 180);
  const ConstParticleView p = store.view();
  std::unordered_set<std::uint64_t> occupied;
  for (auto _ : state) {
    occupied.clear();
    for (std::size_t i = 0; i < n; ++i) occupied.insert(bins.bin_of(p.x[i], p.y[i], p.theta[i]));
    benchmark::DoNotOptimize(kld_sample_count(occupied.size(), KldConfig{}));
  }
  set_particle_rate(state, n);
}

// 10k particles x 60 beams on the recorded Intel map: expected ranges cast by Embree from a
// tracking cloud (0.3 m, 0.2 rad around one free pose) or from particles spread over the whole
// free space; readings cast from the cloud's centre with 5 cm noise, every 20th one short.
struct BeamWorkload {
  static constexpr std::size_t kParticles = 10000;
  static constexpr int kBeams = 60;
  static constexpr float kRangeMax = 81.83F;  // the Intel scanner's no-return reading

  std::vector<float> ranges;    // m, one scan
  std::vector<float> expected;  // m, particle-major
  std::vector<float> logw = std::vector<float>(kParticles, 0.0F);
  BeamModelParams params;

  BeamWorkload(const OccupancyGrid& grid, bool global) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<> u(0.0, 1.0);
    std::normal_distribution<> n(0.0, 1.0);
    const auto& free = grid.free_cells();
    const auto pick = [&] {
      return static_cast<std::size_t>(u(rng) * static_cast<double>(free.size())) % free.size();
    };
    const Point2 centre = grid.free_point(pick(), 0.5, 0.5);
    const double heading = (2.0 * u(rng) - 1.0) * std::numbers::pi;
    std::vector<float> x{static_cast<float>(centre.x)};
    std::vector<float> y{static_cast<float>(centre.y)};
    std::vector<float> theta{static_cast<float>(heading)};
    std::vector<float> angles;
    for (int b = 0; b < kBeams; ++b) {
      angles.push_back(static_cast<float>(std::numbers::pi * (b / (kBeams - 1.0) - 0.5)));
    }
    const RayCaster caster(grid);
    ranges.resize(kBeams);
    caster.cast({x, y, theta, angles, {}, kRangeMax}, ranges);
    for (std::size_t b = 0; b < ranges.size(); ++b) {
      const double noisy = ranges[b] + 0.05 * n(rng);
      const double reading = b % 20 == 0 ? u(rng) * noisy : noisy;
      ranges[b] = std::min(kRangeMax, static_cast<float>(std::max(0.0, reading)));
    }
    for (std::size_t i = 1; i < kParticles; ++i) {
      const Point2 p = global ? grid.free_point(pick(), u(rng), u(rng))
                              : Point2{centre.x + 0.3 * n(rng), centre.y + 0.3 * n(rng)};
      x.push_back(static_cast<float>(p.x));
      y.push_back(static_cast<float>(p.y));
      theta.push_back(static_cast<float>(global ? (2.0 * u(rng) - 1.0) * std::numbers::pi
                                                : heading + 0.2 * n(rng)));
    }
    expected.resize(kParticles * kBeams);
    caster.cast({x, y, theta, angles, {}, kRangeMax}, expected);
  }
};

/// The Intel map, loaded once per process; nullptr when the data folder is absent.
const OccupancyGrid* intel_map() {
  static const std::unique_ptr<OccupancyGrid> grid = [] {
    const auto path = data_dir() / "intel/intel.yaml";
    return std::filesystem::exists(path) ? std::make_unique<OccupancyGrid>(load_map(path))
                                         : nullptr;
  }();
  return grid.get();
}

template <class Weigh>
void run_beam_likelihood(benchmark::State& state, const Weigh& weigh) {
  const OccupancyGrid* grid = intel_map();
  if (grid == nullptr) {
    state.SkipWithError("recorded Intel map not found (set MOTE_DATA_DIR)");
    return;
  }
  BeamWorkload w(*grid, state.range(0) == 1);
  for (auto _ : state) {
    weigh(w);
    benchmark::DoNotOptimize(w.logw.data());
    benchmark::ClobberMemory();
  }
  state.counters["particle_beams"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(w.expected.size()),
      benchmark::Counter::kIsRate);
  state.SetLabel(state.range(0) == 1 ? "intel global" : "intel tracking");
}

// The loop BeamModel::weigh ran before the batched likelihood: particle-outer, one scalar
// double beam_log_likelihood per particle and beam.
void BM_BeamModel_LikelihoodScalar(benchmark::State& state) {
  run_beam_likelihood(state, [](BeamWorkload& w) {
    const std::size_t beams = w.ranges.size();
    for (std::size_t p = 0; p < w.logw.size(); ++p) {
      const float* z_star = w.expected.data() + p * beams;
      double log_likelihood = 0.0;
      for (std::size_t b = 0; b < beams; ++b) {
        log_likelihood +=
            beam_log_likelihood(w.ranges[b], z_star[b], BeamWorkload::kRangeMax, w.params.mixture);
      }
      w.logw[p] += static_cast<float>(w.params.tempering * log_likelihood);
    }
  });
}

void BM_BeamModel_LikelihoodBatched(benchmark::State& state) {
  run_beam_likelihood(state, [](BeamWorkload& w) {
    add_beam_log_likelihoods(w.ranges, BeamWorkload::kRangeMax, w.expected, w.params, w.logw);
  });
}

void beam_cases(benchmark::internal::Benchmark* b) {
  b->ArgNames({"global"})->Arg(0)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Weights_Normalize)->Apply(particle_thread_grid);
BENCHMARK(BM_Weights_NormalizeNaive)->Apply(particle_grid);
BENCHMARK(BM_Kld_CountBins)->Apply(particle_thread_grid);
BENCHMARK(BM_Kld_CountBinsBigMap)->Apply(particle_thread_grid);
BENCHMARK(BM_Kld_CountBinsHashSet)->Apply(particle_grid);
BENCHMARK(BM_BeamModel_LikelihoodScalar)->Apply(beam_cases);
BENCHMARK(BM_BeamModel_LikelihoodBatched)->Apply(beam_cases);

}  // namespace
}  // namespace mote::bench
