// Normalization (log-sum-exp over the deterministic tree, ESS) against a naive serial pass
// with std::exp in double; and KLD bin counting against a serial hash set of bin keys.

#include <unordered_set>
#include <vector>

#include "bench_engine_util.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/weights.hpp"

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

void BM_Kld_CountBins(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ParticleStore store = random_store(n);
  KldBins bins({-20.0, -20.0, 20.0, 20.0}, 0.5, 0.5, 10.0 * 3.14159265 / 180);
  const Executor ex(static_cast<int>(state.range(1)));
  const KldConfig config;
  ex([&] {
    for (auto _ : state) benchmark::DoNotOptimize(kld_sample_count(store.view(), bins, config));
  });
  set_particle_rate(state, n);
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

BENCHMARK(BM_Weights_Normalize)->Apply(particle_thread_grid);
BENCHMARK(BM_Weights_NormalizeNaive)->Apply(particle_grid);
BENCHMARK(BM_Kld_CountBins)->Apply(particle_thread_grid);
BENCHMARK(BM_Kld_CountBinsHashSet)->Apply(particle_grid);

}  // namespace
}  // namespace mote::bench
