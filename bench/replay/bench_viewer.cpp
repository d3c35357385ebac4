// What `mote replay --viewer` records costs (issue 20: under 5% of the replay's time). Each
// iteration replays the whole Intel log; "off" runs it without a hook (baseline), "viewer" with
// the ViewerRecorder, timing record() inside the same run: recording_share is its time over the
// rest of the replay loop, a ratio taken in one run and so robust to a noisy machine.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "mote/maps/map_loader.hpp"
#include "mote/replay/replay_run.hpp"
#include "mote/replay/viewer.hpp"
#include "mote_bench/data.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The Intel log with mote's defaults; particles > 0 fixes the count (min = max).
mote::replay::ReplayOptions intel(int particles) {
  const fs::path dir = mote::bench::data_dir() / "intel";
  mote::replay::ReplayOptions o;
  o.map = dir / "intel.yaml";
  o.log = dir / "intel.clf";
  o.reference = dir / "intel.gt.tum";
  if (particles > 0) o.config.min_particles = o.config.max_particles = particles;
  return o;
}

void BM_Viewer_ReplayIntel(benchmark::State& state, bool record) {
  mote::replay::ReplayOptions options = intel(static_cast<int>(state.range(0)));
  if (!fs::exists(options.log)) {
    state.SkipWithError(("recorded data not found: " + options.log.string()).c_str());
    return;
  }
  const mote::OccupancyGrid map = mote::load_map(options.map);
  double loop_s = 0.0, record_s = 0.0, updates = 0.0, update_ms = 0.0;
  for (auto _ : state) {
    mote::replay::ViewerRecorder recorder(map);
    if (record) {
      options.on_update = [&](const mote::Localizer& filter, const mote::logs::ScanFrame& f) {
        const auto start = Clock::now();
        recorder.record(filter, f);
        record_s += std::chrono::duration<double>(Clock::now() - start).count();
      };
    }
    const mote::replay::ReplayResult result = mote::replay::run_replay(options);
    loop_s += result.wall_s;
    updates += static_cast<double>(result.updates.size());
    for (const mote::replay::UpdateRecord& u : result.updates) update_ms += u.ms.total;
    benchmark::DoNotOptimize(recorder.recording().particles.data());
  }
  state.counters["updates/s"] = benchmark::Counter(updates / loop_s);
  state.counters["update_us"] = benchmark::Counter(1e3 * update_ms / updates);
  state.counters["record_us"] = benchmark::Counter(1e6 * record_s / updates);
  state.counters["recording_share"] = benchmark::Counter(record_s / (loop_s - record_s));
}
BENCHMARK_CAPTURE(BM_Viewer_ReplayIntel, off, false)
    ->Arg(0)
    ->Arg(5000)
    ->ArgName("particles")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Viewer_ReplayIntel, viewer, true)
    ->Arg(0)
    ->Arg(5000)
    ->ArgName("particles")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
