// End-to-end benchmark (issue 7): one full Localizer::update() per iteration (motion, sensor,
// normalize, resample, estimate) on a real map, with the odometry and scan of a simulated drive.
// The particle count is fixed per case (min = max, so KLD never changes it) except in the
// "/kld_min:" cases (KLD-adaptive between 500 and n), and every update resamples (ESS fraction
// 1), so each case measures the phases its name says.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <string>

#include "e2e_cases.hpp"
#include "e2e_machine.hpp"
#include "e2e_refine.hpp"
#include "e2e_world.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/engine/particles.hpp"

namespace mote::bench {

namespace {

// The largest beam count of the suite: the filter uses every beam of a scan, so one filter
// serves every beam count (the scans carry exactly the case's beams).
constexpr int kMaxBeams = 180;

LocalizerConfig config_for(const Case& c) {
  LocalizerConfig config = c.nav2 ? nav2_defaults() : LocalizerConfig{};
  config.laser_model_type = c.model;
  config.min_particles = config.max_particles = c.particles;
  if (c.kld_min > 0) config.min_particles = c.kld_min;
  config.ray_casting = c.ray_casting;
  config.threads = c.threads;
  config.max_beams = kMaxBeams;
  config.update_min_d = config.update_min_a = 0.0;  // every frame of the drive updates
  config.resample_interval = 1;
  config.resample_ess_fraction = 1.0;  // ESS < N after any informative scan: always resample
  return config;
}

// The filter of the last case. Building it (map copy, distance field or Embree scene) is set-up:
// consecutive cases with the same model, particle count and threads reuse it.
struct FilterSlot {
  LaserModel model = LaserModel::kLikelihoodField;
  int particles = 0;
  int threads = 0;
  bool nav2 = false;
  int kld_min = 0;
  RayCasting ray_casting = RayCasting::kExact;
  std::unique_ptr<Localizer> filter;
  bool tracking = false;  // particles follow the drive; k is the last frame's update index
  std::uint64_t k = 0;
};

void use_filter(FilterSlot& slot, const Case& c) {
  if (!slot.filter || slot.model != c.model || slot.particles != c.particles ||
      slot.threads != c.threads || slot.nav2 != c.nav2 || slot.kld_min != c.kld_min ||
      slot.ray_casting != c.ray_casting) {
    slot.filter.reset();  // free the old particle set before allocating the new one
    slot.filter = std::make_unique<Localizer>(world().map, config_for(c));
    slot.model = c.model;
    slot.particles = c.particles;
    slot.threads = c.threads;
    slot.nav2 = c.nav2;
    slot.kld_min = c.kld_min;
    slot.ray_casting = c.ray_casting;
    slot.tracking = false;
    slot.k = 0;
  }
}

// Particles around the true pose (0.1 m, 3 degrees), then the first scan: the state a tracking
// filter is in. Only done when the slot's filter is not already tracking the drive.
void start_tracking(FilterSlot& slot, int beams) {
  const World& w = world();
  const std::size_t f = w.frame(slot.k);
  slot.filter->initialize(w.truth[f], Eigen::Vector3d(0.01, 0.01, 0.003).asDiagonal());
  slot.filter->update(w.odometry[f], w.scan(beams, f));
  slot.tracking = true;
}

/// What the timed updates add up to.
struct Totals {
  PhaseTimes ms;
  double particle_beams = 0.0;
  double particles = 0.0;  // after each update: what KLD chose in the adaptive cases
  double resampled = 0.0;
  double tempering_trials = 0.0;
  std::string failure;  // set when an update did not run the full filter

  void add(const UpdateStats& s) {
    if (s.outcome != UpdateOutcome::kUpdated) failure = "update did not run: " + s.reason;
    ms.motion += s.ms.motion;
    ms.sensor += s.ms.sensor;
    ms.normalize += s.ms.normalize;
    ms.resample += s.ms.resample;
    ms.estimate += s.ms.estimate;
    ms.total += s.ms.total;
    particles += static_cast<double>(s.particles);
    particle_beams += static_cast<double>(s.weighed) * static_cast<double>(s.beams);
    resampled += s.resampled ? 1.0 : 0.0;
    tempering_trials += s.tempering_trials;
  }
};

void run_tracking(benchmark::State& state, FilterSlot& slot, const Case& c, Totals& totals) {
  const World& w = world();
  if (!slot.tracking) start_tracking(slot, c.beams);
  for (auto _ : state) {
    const std::size_t f = w.frame(++slot.k);
    slot.filter->update(w.odometry[f], w.scan(c.beams, f));
    totals.add(slot.filter->last_update());
  }
  const Pose2 truth = w.truth[w.frame(slot.k)];
  const Pose2 best = slot.filter->estimate().best().mean;
  // In millimetres: the console prints every counter with an SI prefix below 0.01, so an error
  // of 3.4 mm counted in metres reads "err_m=3.3953m", which was taken for 3.4 metres.
  state.counters["err_mm"] = 1e3 * std::hypot(best.x - truth.x, best.y - truth.y);
}

// Each timed update starts from particles uniform over free space. The untimed first update
// after initialize_global() only weighs (no motion, no resampling), so one beam suffices.
void run_global(benchmark::State& state, FilterSlot& slot, const Case& c, Totals& totals) {
  const World& w = world();
  slot.tracking = false;
  for (auto _ : state) {
    state.PauseTiming();
    const std::size_t f = w.frame(slot.k++);
    slot.filter->initialize_global();
    slot.filter->update(w.odometry[f], middle_beam(w.scan(c.beams, f)));
    const std::size_t g = w.frame(slot.k);
    state.ResumeTiming();
    slot.filter->update(w.odometry[g], w.scan(c.beams, g));
    totals.add(slot.filter->last_update());
  }
}

// Per particle: both particle buffers (x, y, theta, log-weight floats) and the two 64-bit
// resampling scratch columns of capacity + 1 entries (particles.hpp), the Localizer's untempered
// log-likelihood column (a float per padded particle), and the estimate's summarizer (a float
// weight, a 64-bit bin key and a 32-bit bin number per particle: 16 bytes).
double bytes_per_particle(int particles) {
  ParticleStore store;
  store.reserve(static_cast<std::size_t>(particles));
  const auto cap = static_cast<double>(store.capacity());
  const double store_bytes =
      2.0 * 4.0 * sizeof(float) * cap + 2.0 * sizeof(std::uint64_t) * (cap + 1.0);
  const double loglik = sizeof(float) * static_cast<double>(pad_particles(store.capacity()));
  const double summarizer = (sizeof(float) + sizeof(std::uint64_t) + sizeof(std::uint32_t)) *
                            static_cast<double>(particles);
  return (store_bytes + loglik + summarizer) / particles;
}

void set_counters(benchmark::State& state, const Case& c, const Totals& t) {
  using benchmark::Counter;
  const auto iters = static_cast<double>(state.iterations());
  // ms summed -> ns per weighed particle (the KLD cases weigh fewer than n).
  const double weighed = t.particle_beams / c.beams;
  const double per_particle = weighed > 0.0 ? 1e6 / weighed : 0.0;
  state.counters["updates/s"] = Counter(iters, Counter::kIsRate);
  // particle_beams/s: particles x beams weighed over the Localizer's own update time (the sum of
  // UpdateStats::ms.total), the definition report.json's particle_beams_per_s uses too.
  const double update_s = t.ms.total * 1e-3;
  state.counters["particle_beams/s"] = update_s > 0.0 ? t.particle_beams / update_s : 0.0;
  // The beam model casts one ray per particle and beam (Thrun table 6.1).
  if (c.model == LaserModel::kBeam) {
    state.counters["rays/s"] = update_s > 0.0 ? t.particle_beams / update_s : 0.0;
  }
  state.counters["particles"] = t.particles / iters;
  state.counters["ns_motion/p"] = t.ms.motion * per_particle;
  state.counters["ns_sensor/p"] = t.ms.sensor * per_particle;
  // Normalization with the tempering search (its ESS trials, counted below) and the scan fit.
  state.counters["ns_normalize/p"] = t.ms.normalize * per_particle;
  state.counters["tempering_trials"] = t.tempering_trials / iters;
  state.counters["ns_resample/p"] = t.ms.resample * per_particle;
  state.counters["ns_estimate/p"] = t.ms.estimate * per_particle;
  state.counters["bytes/p"] = bytes_per_particle(c.particles);
  state.counters["resampled"] = t.resampled / iters;
}

void BM_Localizer_Update(benchmark::State& state, const Case& c) {
  static FilterSlot slot;
  use_filter(slot, c);
  Totals totals;
  if (c.setting == Setting::kTracking) {
    run_tracking(state, slot, c, totals);
  } else {
    run_global(state, slot, c, totals);
  }
  if (!totals.failure.empty()) {
    state.SkipWithError(totals.failure.c_str());
    return;
  }
  set_counters(state, c, totals);
}

}  // namespace

}  // namespace mote::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("map", mote::bench::world().map_name);
  mote::bench::register_machine_check("start");
  for (const mote::bench::Case& c : mote::bench::all_cases()) {
    benchmark::RegisterBenchmark(c.name().c_str(), mote::bench::BM_Localizer_Update, c)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  // Mote's defaults beside nav2's in one run: what the adaptive mechanisms cost.
  for (const mote::bench::Case& c : mote::bench::nav2_baseline_cases()) {
    const std::string name = c.name() + (c.nav2 ? "" : "/defaults:mote");
    benchmark::RegisterBenchmark(name.c_str(), mote::bench::BM_Localizer_Update, c)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  // The beam model with exact casting beside the range table (issue 19).
  for (const mote::bench::Case& c : mote::bench::range_table_cases()) {
    const std::string name =
        c.name() + (c.ray_casting == mote::RayCasting::kExact ? "/ray_casting:exact" : "");
    benchmark::RegisterBenchmark(name.c_str(), mote::bench::BM_Localizer_Update, c)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  // KLD-adaptive twins of the headline cases (min 500 particles, max n).
  for (const mote::bench::Case& c : mote::bench::kld_cases()) {
    benchmark::RegisterBenchmark(c.name().c_str(), mote::bench::BM_Localizer_Update, c)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  // The refined estimate's scan match alone, to read its share of the tracking updates above.
  mote::bench::register_refine_cases();
  mote::bench::register_machine_check("end");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
