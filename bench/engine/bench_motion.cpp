// Motion update throughput: the vectorized Philox + polynomial kernels against a naive scalar
// loop with std::normal_distribution and libm sin/cos (the form design.md section 4 warns of).

#include <random>

#include "bench_engine_util.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/motion.hpp"

namespace mote::bench {
namespace {

const Odometry kStep{{0.0, 0.0, 0.0}, {0.2, 0.05, 0.1}};

template <class Model>
void run_predict(benchmark::State& state, const Model& model) {
  const auto n = static_cast<std::size_t>(state.range(0));
  ParticleStore store = random_store(n);
  const Executor ex(static_cast<int>(state.range(1)));
  std::uint64_t step = 0;
  ex([&] {
    for (auto _ : state) {
      predict(model, kStep, store.view(), 7, ++step);
      benchmark::ClobberMemory();
    }
  });
  set_particle_rate(state, n);
}

void BM_Motion_Odometry(benchmark::State& state) { run_predict(state, OdometryModel{}); }
void BM_Motion_Omni(benchmark::State& state) { run_predict(state, OmniModel{}); }
void BM_Motion_Ackermann(benchmark::State& state) { run_predict(state, AckermannModel{}); }

// Baseline: table 5.6 as usually written, serial, std::mt19937 + std::normal_distribution.
void BM_Motion_OdometryNaive(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  ParticleStore store = random_store(n);
  const ParticleView p = store.view();
  std::mt19937 gen(7);
  std::normal_distribution<float> normal;
  const float rot1 = 0.24F, trans = 0.206F, rot2 = -0.14F, sd = 0.05F;
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) {
      const float r1 = rot1 - sd * normal(gen);
      const float t = trans - sd * normal(gen);
      const float r2 = rot2 - sd * normal(gen);
      p.x[i] += t * std::cos(p.theta[i] + r1);
      p.y[i] += t * std::sin(p.theta[i] + r1);
      p.theta[i] = static_cast<float>(wrap_angle(p.theta[i] + r1 + r2));
    }
    benchmark::ClobberMemory();
  }
  set_particle_rate(state, n);
}

BENCHMARK(BM_Motion_Odometry)->Apply(particle_thread_grid);
BENCHMARK(BM_Motion_Omni)->Apply(particle_thread_grid);
BENCHMARK(BM_Motion_Ackermann)->Apply(particle_thread_grid);
BENCHMARK(BM_Motion_OdometryNaive)->Apply(particle_grid);

// How many cores the machine gives right now (design.md section 4): a fixed compute loop over
// 1M elements; compare its 1- and 2-thread rates before quoting any 2-thread figure.
void BM_Machine_ComputeLoop(benchmark::State& state) {
  constexpr std::size_t kN = 1 << 20;
  std::vector<float> data(kN, 0.5F);
  const Executor ex(static_cast<int>(state.range(0)));
  ex([&] {
    for (auto _ : state) {
      for_each_particle_chunk(kN, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          float v = data[i];
          for (int k = 0; k < 64; ++k) v = v * 0.999F + 0.0001F;
          data[i] = v;
        }
      });
      benchmark::ClobberMemory();
    }
  });
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kN);
}
BENCHMARK(BM_Machine_ComputeLoop)->Arg(1)->Arg(2)->ArgName("threads")->UseRealTime();

}  // namespace
}  // namespace mote::bench

BENCHMARK_MAIN();
