#pragma once
// Shared set-up for the engine benchmarks: particle sets with realistic spread and weights,
// and the argument grid (1k to 1M particles, 1 and 2 threads).

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>

#include "mote/engine/particles.hpp"
#include "mote/engine/philox.hpp"

namespace mote::bench {

/// n particles spread over a 40 m x 40 m area with random headings and log-weights.
inline ParticleStore random_store(std::size_t n) {
  ParticleStore store(n);
  const ParticleView p = store.view();
  const RngStream rng{1, 0, RngPurpose::kUser};
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<float, 4> u = rng.uniform4(static_cast<std::uint32_t>(i));
    p.x[i] = 40.0F * u[0] - 20.0F;
    p.y[i] = 40.0F * u[1] - 20.0F;
    p.theta[i] = 6.2831853F * u[2] - 3.1415926F;
    p.logw[i] = -20.0F * u[3];
  }
  return store;
}

/// Particle counts x thread counts.
inline void particle_thread_grid(benchmark::internal::Benchmark* b) {
  for (const int threads : {1, 2}) {
    for (const int n : {1000, 10000, 100000, 1000000}) b->Args({n, threads});
  }
  b->ArgNames({"n", "threads"})->UseRealTime()->Unit(benchmark::kMicrosecond);
}

/// Particle counts only (serial baselines).
inline void particle_grid(benchmark::internal::Benchmark* b) {
  for (const int n : {1000, 10000, 100000, 1000000}) b->Args({n});
  b->ArgNames({"n"})->UseRealTime()->Unit(benchmark::kMicrosecond);
}

inline void set_particle_rate(benchmark::State& state, std::size_t n) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(n));
}

}  // namespace mote::bench
