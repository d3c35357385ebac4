#include "e2e_machine.hpp"

#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <array>
#include <string>
#include <vector>

namespace mote::bench {

namespace {

// 64 independent multiply-add chains: no memory traffic and no sharing, so 2 threads take half
// the time of 1 whenever the machine really gives the process 2 cores.
void BM_Machine_ComputeLoop(benchmark::State& state, int threads) {
  tbb::task_arena arena(threads);
  constexpr int kTasks = 64;
  constexpr int kSteps = 200'000;
  std::vector<double> sink(kTasks);
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(/*first=*/0, /*last=*/kTasks, /*f=*/[&](int t) {
        double v = t;
        for (int k = 0; k < kSteps; ++k) v = v * 1.0000001 + 1e-9;
        sink[static_cast<std::size_t>(t)] = v;
      });
    });
    benchmark::DoNotOptimize(sink.data());
  }
  state.SetItemsProcessed(state.iterations() * kTasks * kSteps);
}

// The same shape with 128 independent float chains per task: enough to keep the vector FMA
// units busy rather than waiting on latency. The compute loop scales 2x on two hyperthreads of
// one core too (each waits on its own chain); this one does so only on two real cores, which
// is what the vectorized kernels (motion, likelihood field, weights) need.
void BM_Machine_VectorLoop(benchmark::State& state, int threads) {
  tbb::task_arena arena(threads);
  constexpr int kTasks = 64;
  constexpr int kSteps = 20'000;
  constexpr int kChains = 128;
  std::vector<float> sink(kTasks);
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(/*first=*/0, /*last=*/kTasks, /*f=*/[&](int t) {
        std::array<float, kChains> v{};
        v.fill(static_cast<float>(t));
        for (int k = 0; k < kSteps; ++k) {
          for (float& x : v) x = x * 0.9999999F + 1e-7F;
        }
        float sum = 0.0F;
        for (const float x : v) sum += x;
        sink[static_cast<std::size_t>(t)] = sum;
      });
    });
    benchmark::DoNotOptimize(sink.data());
  }
  state.SetItemsProcessed(state.iterations() * kTasks * kSteps * kChains);
}

void register_loop(const char* loop, void (*body)(benchmark::State&, int), const char* when) {
  for (const int threads : {1, 2}) {
    const std::string name =
        std::string("BM_Machine_") + loop + "/" + when + "/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(name.c_str(), body, threads)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

void register_machine_check(const char* when) {
  register_loop("ComputeLoop", BM_Machine_ComputeLoop, when);
  register_loop("VectorLoop", BM_Machine_VectorLoop, when);
}

}  // namespace mote::bench
