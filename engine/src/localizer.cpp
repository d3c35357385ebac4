// The MCL update of design.md section 2 as a straight list of calls.
#include "mote/engine/localizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "localizer_impl.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/resample.hpp"

namespace mote {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Runs f and adds its wall time to `ms`.
template <class F>
void timed(double& ms, F&& f) {
  const auto start = Clock::now();
  f();
  ms += ms_since(start);
}

}  // namespace

Localizer::Localizer(const OccupancyGrid& map, LocalizerConfig config)
    : impl_(std::make_unique<Impl>(std::make_shared<const OccupancyGrid>(map), std::move(config))) {
}
Localizer::Localizer(std::shared_ptr<const OccupancyGrid> map, LocalizerConfig config)
    : impl_(std::make_unique<Impl>(std::move(map), std::move(config))) {}
Localizer::~Localizer() = default;
Localizer::Localizer(Localizer&&) noexcept = default;
Localizer& Localizer::operator=(Localizer&&) noexcept = default;

double Localizer::Impl::free_bins() const {
  // KLD bins of free space: free area over the bin area, times the heading bins.
  const double cell_area = map.resolution() * map.resolution();
  const double xy_bins = static_cast<double>(map.free_cell_count()) * cell_area /
                         (config.kld_bin_xy * config.kld_bin_xy);
  const double theta_bins = std::ceil(2.0 * std::numbers::pi / config.kld_bin_theta);
  return xy_bins * theta_bins;
}

std::size_t Localizer::Impl::global_count() const {
  const auto max_n = static_cast<std::size_t>(config.max_particles);
  if (config.global_particles_per_bin <= 0.0) return max_n;
  const double wanted = std::ceil(config.global_particles_per_bin * free_bins());
  return static_cast<std::size_t>(
      std::clamp(wanted, static_cast<double>(config.min_particles), static_cast<double>(max_n)));
}

void Localizer::Impl::keep_kld_prefix() {
  // The Gaussian draws are independent, so any prefix of them is a sample of its own: keep the
  // shortest prefix that Fox's rule finds large enough for the bins it occupies.
  if (kld.min_particles == kld.max_particles) return;
  std::size_t n = kld.min_particles;
  while (n < store.size()) {
    ConstParticleView prefix = std::as_const(store).view();
    prefix.count = n;
    const std::size_t wanted = kld_sample_count(bins.count(prefix, config.grain), kld);
    if (wanted <= n) break;
    n = std::min(wanted, store.size());
  }
  store.resize(n);
  store.set_uniform_weights();
}

void Localizer::Impl::start_fresh(bool settled) {
  step = 0;
  has_odometry = false;
  degenerate = false;
  updates_since_resample = 0;
  recovery.reset();
  monitor.forget();
  reset_relocalization(settled);
  focus_judged = false;
  odometry_noise.reset();
  last_fix = {};
  correlation = 0.0;
  has_held = false;
  belief_places = 0;
  place_anchors.clear();
  place_evidence.clear();
  hold.end();
  motion = make_motion(config);
  stats = UpdateStats{};
  stats.particles = store.size();
  initialized = true;
  executor.run([&] { update_estimate(); });
  // No scan has been matched to the new belief: the refined estimate is its best hypothesis,
  // unrefined and without a covariance (nothing of the previous run's, which a live node
  // publishing after a reset would otherwise send), and the state is the monitor's fresh one.
  estimate.refined = ScanMatch{.pose = estimate.best().mean};
  stats.state = monitor.state();
  stats.lost_bound = monitor.lost_bound();
}

void Localizer::initialize(const Pose2& mean, const Eigen::Matrix3d& covariance) {
  Impl& s = *impl_;
  if (!is_finite(mean)) throw ConfigError("Localizer::initialize: the mean pose is not finite");
  s.executor.run([&] {
    initialize_gaussian(s.store, static_cast<std::size_t>(s.config.max_particles), mean, covariance,
                        s.config.seed, s.config.grain);
    if (s.config.global_particles_per_bin > 0.0) s.keep_kld_prefix();
  });
  s.start_fresh(true);
}

void Localizer::initialize_global() {
  Impl& s = *impl_;
  s.executor.run(
      [&] { initialize_uniform(s.store, s.global_count(), s.map, s.config.seed, s.config.grain); });
  s.start_fresh(false);
}

void Localizer::Impl::run_filter(const Pose2& odometry) {
  // The checks before this leave nothing here that throws for a well-formed call; should it
  // throw anyway (out of memory), the motion already applied counts as applied, so the next
  // update does not apply it again (localizer.hpp).
  bool moved = false;
  try {
    executor.run([&] {
      if (has_odometry) {
        timed(stats.ms.motion, [&] {
          maybe_relocalize();
          predict(odometry);
        });
      }
      moved = has_odometry;
      timed(stats.ms.sensor, [&] {
        if (!focus_judged) judge_focus();
        place_prior(odometry);
        drop_blocked_beams();
        weigh();
      });
      timed(stats.ms.normalize, [&] {
        temper();
        normalize();
      });
      timed(stats.ms.resample, [&] {
        weigh_places();
        maybe_resample();
        maybe_inject();
      });
      timed(stats.ms.estimate, [&] {
        update_estimate();
        keep_places(odometry);
        judge_focus();
        judge_localization();
      });
    });
  } catch (...) {
    if (moved) {
      if (has_held) held = compose(held, between(last_odometry, odometry));  // carried as well
      last_odometry = odometry;
      last_fix = {};  // no residual across the failed update
      ++step;
    }
    throw;
  }
}

bool Localizer::update(const Pose2& odometry, const LaserScan& scan) {
  Impl& s = *impl_;
  const auto start = Clock::now();
  s.stats = UpdateStats{};
  s.stats.lost_bound = s.monitor.lost_bound();
  s.stats.step = s.step;
  s.stats.particles = s.store.size();
  if (!s.initialized) throw Error("Localizer::update called before initialize()");
  if (!is_finite(odometry))
    return s.reject(UpdateOutcome::kRejectedOdometry, "odometry pose is not finite");
  if (const std::string problem = scan_geometry_problem(scan); !problem.empty())
    return s.reject(UpdateOutcome::kRejectedScan, problem);
  if (std::string problem = s.select(scan); !problem.empty())
    return s.reject(UpdateOutcome::kRejectedScan, std::move(problem));
  if (s.has_odometry && s.jumped(odometry)) return s.reset_odometry(odometry);
  if (s.has_odometry && !s.force_update && !s.moved_enough(odometry) && !s.still_update_due(scan)) {
    return s.reject(UpdateOutcome::kNotMoved, "");
  }
  s.select_endpoints(scan);  // every reading's endpoint: only for a scan the filter runs on

  s.force_update = false;
  s.run_filter(odometry);
  s.hold_reported_place(odometry);
  s.stats.outcome = s.degenerate     ? UpdateOutcome::kUnexplainedScan
                    : s.has_odometry ? UpdateOutcome::kUpdated
                                     : UpdateOutcome::kInitialized;
  s.count_lost_updates();
  s.adapt_motion_noise(odometry);
  s.last_odometry = odometry;
  s.has_odometry = true;
  ++s.step;
  s.stats.step = s.step;
  s.stats.particles = s.store.size();
  s.stats.ms.total = ms_since(start);
  return true;
}

void Localizer::force_next_update() noexcept { impl_->force_update = true; }

GlobalSetSize Localizer::global_set() const noexcept {
  const Impl& s = *impl_;
  const std::size_t n = s.global_count();
  const double bins = s.free_bins();
  return {.particles = n,
          .per_bin = bins > 0.0 ? static_cast<double>(n) / bins : 0.0,
          .capped = s.config.global_particles_per_bin > 0.0 &&
                    s.config.global_particles_per_bin * bins >
                        static_cast<double>(s.config.max_particles)};
}

const LocalizationEstimate& Localizer::estimate() const noexcept { return impl_->estimate; }
ConstParticleView Localizer::particles() const noexcept {
  return std::as_const(impl_->store).view();
}
const UpdateStats& Localizer::last_update() const noexcept { return impl_->stats; }
const LocalizerConfig& Localizer::config() const noexcept { return impl_->config; }
int Localizer::threads() const noexcept { return impl_->executor.threads(); }

const RangeTable* Localizer::range_table() const noexcept {
  const auto* beam = impl_->sensor ? std::get_if<BeamModel>(impl_->sensor.get()) : nullptr;
  return beam != nullptr ? beam->range_table() : nullptr;
}

std::optional<BeamCasting> Localizer::beam_casting() const noexcept {
  const auto* beam = impl_->sensor ? std::get_if<BeamModel>(impl_->sensor.get()) : nullptr;
  if (beam == nullptr) return std::nullopt;
  return beam->casting();
}

}  // namespace mote
