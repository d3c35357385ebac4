// The MCL update of design.md section 2 as a straight list of calls.
#include "mote/engine/localizer.hpp"

#include <chrono>
#include <cmath>
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
    : impl_(std::make_unique<Impl>(map, std::move(config))) {}
Localizer::~Localizer() = default;
Localizer::Localizer(Localizer&&) noexcept = default;
Localizer& Localizer::operator=(Localizer&&) noexcept = default;

void Localizer::Impl::start_fresh() {
  step = 0;
  has_odometry = false;
  degenerate = false;
  updates_since_resample = 0;
  recovery.reset();
  stats = UpdateStats{};
  stats.particles = store.size();
  initialized = true;
  executor.run([&] { update_estimate(); });
}

void Localizer::initialize(const Pose2& mean, const Eigen::Matrix3d& covariance) {
  Impl& s = *impl_;
  if (!is_finite(mean)) throw ConfigError("Localizer::initialize: the mean pose is not finite");
  s.executor.run([&] {
    initialize_gaussian(s.store, static_cast<std::size_t>(s.config.max_particles), mean, covariance,
                        s.config.seed, s.config.grain);
  });
  s.start_fresh();
}

void Localizer::initialize_global() {
  Impl& s = *impl_;
  s.executor.run([&] {
    initialize_uniform(s.store, static_cast<std::size_t>(s.config.max_particles), s.map,
                       s.config.seed, s.config.grain);
  });
  s.start_fresh();
}

bool Localizer::update(const Pose2& odometry, const LaserScan& scan) {
  Impl& s = *impl_;
  const auto start = Clock::now();
  s.stats = UpdateStats{};
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
  if (s.has_odometry && !s.moved_enough(odometry)) return s.reject(UpdateOutcome::kNotMoved, "");

  // The checks above leave nothing in this block that throws for a well-formed call; should it
  // throw anyway (out of memory), the motion already applied counts as applied, so the next
  // update does not apply it again (localizer.hpp).
  bool moved = false;
  try {
    s.executor.run([&] {
      if (s.has_odometry) timed(s.stats.ms.motion, [&] { s.predict(odometry); });
      moved = s.has_odometry;
      timed(s.stats.ms.sensor, [&] { s.weigh(); });
      timed(s.stats.ms.normalize, [&] { s.normalize(); });
      timed(s.stats.ms.resample, [&] { s.maybe_resample(); });
      timed(s.stats.ms.estimate, [&] { s.update_estimate(); });
    });
  } catch (...) {
    if (moved) {
      s.last_odometry = odometry;
      ++s.step;
    }
    throw;
  }
  s.stats.outcome = s.degenerate     ? UpdateOutcome::kUnexplainedScan
                    : s.has_odometry ? UpdateOutcome::kUpdated
                                     : UpdateOutcome::kInitialized;
  s.last_odometry = odometry;
  s.has_odometry = true;
  ++s.step;
  s.stats.step = s.step;
  s.stats.particles = s.store.size();
  s.stats.ms.total = ms_since(start);
  return true;
}

const LocalizationEstimate& Localizer::estimate() const noexcept { return impl_->estimate; }
ConstParticleView Localizer::particles() const noexcept {
  return std::as_const(impl_->store).view();
}
const UpdateStats& Localizer::last_update() const noexcept { return impl_->stats; }
const LocalizerConfig& Localizer::config() const noexcept { return impl_->config; }
int Localizer::threads() const noexcept { return impl_->executor.threads(); }

}  // namespace mote
