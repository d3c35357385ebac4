// A full Localizer::update() on the recorded Intel map with a scan ray-cast from a known pose:
// both sensor models, 10k to 1M particles, 60 beams, 1 and 2 threads. Tracking setting: the
// particles start around the true pose; the robot moves 0.3 m between updates.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "mote/engine/localizer.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote_bench/data.hpp"

namespace mote {
namespace {

const OccupancyGrid* intel_map() {
  static const std::unique_ptr<OccupancyGrid> map = [] {
    const auto yaml = bench::data_dir() / "intel/intel.yaml";
    return std::filesystem::exists(yaml) ? std::make_unique<OccupancyGrid>(load_map(yaml))
                                         : nullptr;
  }();
  return map.get();
}

// 181 beams over 180 degrees from `pose`, exact ranges.
LaserScan scan_from(const OccupancyGrid& map, const Pose2& pose) {
  const RayCaster caster(map);
  LaserScan scan;
  scan.angle_min = static_cast<float>(-std::numbers::pi / 2);
  scan.angle_increment = static_cast<float>(std::numbers::pi / 180);
  scan.range_min = 0.05F;
  scan.range_max = 20.0F;
  for (std::size_t b = 0; b < 181; ++b) {
    scan.ranges.push_back(
        caster.cast_one({pose.x, pose.y}, pose.theta + scan.beam_angle(b), 20.0F));
  }
  return scan;
}

void BM_Localizer_Update(benchmark::State& state, LaserModel model) {
  const OccupancyGrid* map = intel_map();
  if (map == nullptr) {
    state.SkipWithError("Intel map not found (set MOTE_DATA_DIR)");
    return;
  }
  const auto particles = static_cast<int>(state.range(0));
  LocalizerConfig config;
  config.min_particles = config.max_particles = particles;
  config.threads = static_cast<int>(state.range(1));
  config.laser_model_type = model;
  config.max_beams = 60;
  config.update_min_d = config.update_min_a = 0.0;
  Localizer filter(*map, config);
  const Pose2 truth{0.6, -0.03, -0.35};
  filter.initialize(truth, Eigen::Vector3d(0.01, 0.01, 0.003).asDiagonal());
  const LaserScan scan = scan_from(*map, truth);
  // Odometry alternates between two poses 0.3 m apart: every update moves, samples, weighs
  // and resamples, while the particles stay near the scan's pose.
  const Pose2 odom[2] = {{0, 0, 0}, {0.3, 0, 0}};
  filter.update(odom[0], scan);
  std::size_t k = 1;
  PhaseTimes sum;
  for (auto _ : state) {
    filter.update(odom[k++ % 2], scan);
    const PhaseTimes& ms = filter.last_update().ms;
    sum.motion += ms.motion;
    sum.sensor += ms.sensor;
    sum.resample += ms.resample;
    sum.estimate += ms.estimate;
  }
  const auto n = static_cast<double>(particles);
  const auto iters = static_cast<double>(state.iterations());
  state.counters["updates/s"] = benchmark::Counter(iters, benchmark::Counter::kIsRate);
  state.counters["particle_beams/s"] =
      benchmark::Counter(iters * n * 60.0, benchmark::Counter::kIsRate);
  state.counters["ns_motion/p"] = sum.motion * 1e6 / (iters * n);
  state.counters["ns_sensor/p"] = sum.sensor * 1e6 / (iters * n);
  state.counters["ns_resample/p"] = sum.resample * 1e6 / (iters * n);
  state.counters["ns_estimate/p"] = sum.estimate * 1e6 / (iters * n);
}

void ParticleAndThreadArgs(benchmark::internal::Benchmark* b, int max_particles) {
  for (int threads : {1, 2}) {
    for (int n = 10'000; n <= max_particles; n *= 10) b->Args({n, threads});
  }
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK_CAPTURE(BM_Localizer_Update, likelihood_field, LaserModel::kLikelihoodField)
    ->Apply([](auto* b) { ParticleAndThreadArgs(b, 1'000'000); });
BENCHMARK_CAPTURE(BM_Localizer_Update, beam, LaserModel::kBeam)->Apply([](auto* b) {
  ParticleAndThreadArgs(b, 100'000);
});

}  // namespace
}  // namespace mote

BENCHMARK_MAIN();
