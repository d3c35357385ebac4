#include "e2e_machine.hpp"

#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

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

}  // namespace

void register_machine_check(const char* when) {
  for (const int threads : {1, 2}) {
    const std::string name =
        std::string("BM_Machine_ComputeLoop/") + when + "/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(name.c_str(), BM_Machine_ComputeLoop, threads)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace mote::bench
