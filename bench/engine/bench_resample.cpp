// Resampling 1k-1M particles: parallel systematic against its serial reference and against
// multinomial (n binary searches). Each iteration restores the same random weights first,
// outside the timed region, so every iteration resamples a realistic weighted set.

#include <algorithm>
#include <vector>

#include "bench_engine_util.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/resample.hpp"
#include "mote/engine/weights.hpp"

namespace mote::bench {
namespace {

template <class Resample>
void run_resample(benchmark::State& state, int threads, const Resample& resample) {
  const auto n = static_cast<std::size_t>(state.range(0));
  ParticleStore store = random_store(n);
  normalize(store.view());
  const std::vector<float> logw(store.view().logw, store.view().logw + n);
  const Executor ex(threads);
  std::uint64_t step = 0;
  ex([&] {
    for (auto _ : state) {
      state.PauseTiming();
      std::copy(logw.begin(), logw.end(), store.view().logw);
      state.ResumeTiming();
      resample(store, n, ++step);
      benchmark::ClobberMemory();
    }
  });
  set_particle_rate(state, n);
}

void BM_Resample_Systematic(benchmark::State& state) {
  run_resample(state, static_cast<int>(state.range(1)),
               [](ParticleStore& s, std::size_t n, std::uint64_t step) {
                 resample_systematic(s, n, 3, step);
               });
}

void BM_Resample_SystematicSerial(benchmark::State& state) {
  run_resample(state, 1, [](ParticleStore& s, std::size_t n, std::uint64_t step) {
    resample_systematic_serial(s, n, 3, step);
  });
}

void BM_Resample_Multinomial(benchmark::State& state) {
  run_resample(state, static_cast<int>(state.range(1)),
               [](ParticleStore& s, std::size_t n, std::uint64_t step) {
                 resample_multinomial(s, n, 3, step);
               });
}

BENCHMARK(BM_Resample_Systematic)->Apply(particle_thread_grid);
BENCHMARK(BM_Resample_SystematicSerial)->Apply(particle_grid);
BENCHMARK(BM_Resample_Multinomial)->Apply(particle_thread_grid);

}  // namespace
}  // namespace mote::bench
