// The steps of one Localizer update (design.md section 2), each a call into a kernel.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "localizer_impl.hpp"
#include "mote/engine/estimate.hpp"
#include "mote/engine/resample.hpp"
#include "mote/engine/weights.hpp"

namespace mote {

namespace {

MotionVariant make_motion(const LocalizerConfig& c) {
  switch (c.odom_model_type) {
    case OdomModel::kOmni:
      return OmniModel{c.alpha1, c.alpha2, c.alpha3, c.alpha4, c.alpha5};
    case OdomModel::kAckermann:
      return AckermannModel{
          .wheelbase = c.wheelbase, .alpha_distance = c.alpha3, .alpha_steering = c.alpha1};
    case OdomModel::kDiff:
      break;
  }
  return OdometryModel{c.alpha1, c.alpha2, c.alpha3, c.alpha4, c.amcl_motion_conventions};
}

MixtureParams mixture_of(const LocalizerConfig& c) {
  return {c.z_hit, c.z_short, c.z_max, c.z_rand, c.sigma_hit, c.lambda_short};
}

SensorVariant make_sensor(const OccupancyGrid& grid, const LocalizerConfig& c) {
  if (c.laser_model_type == LaserModel::kBeam) {
    return SensorVariant(
        std::in_place_type<BeamModel>, grid,
        BeamModelParams{mixture_of(c), c.likelihood_tempering, c.unknown_cells_block_rays});
  }
  return SensorVariant(std::in_place_type<LikelihoodFieldModel>, grid,
                       LikelihoodFieldParams{.mixture = mixture_of(c),
                                             .max_distance = c.laser_likelihood_max_dist,
                                             .combination = c.likelihood_combination,
                                             .tempering = c.likelihood_tempering});
}

KldConfig kld_of(const LocalizerConfig& c) {
  return {.epsilon = c.pf_err,
          .delta = c.kld_z_is_quantile ? 0.01 : 1.0 - c.pf_z,
          .use_z = c.kld_z_is_quantile,
          .z = c.pf_z,
          .bin_x = c.kld_bin_xy,
          .bin_y = c.kld_bin_xy,
          .bin_theta = c.kld_bin_theta,
          .min_particles = static_cast<std::size_t>(c.min_particles),
          .max_particles = static_cast<std::size_t>(c.max_particles)};
}

LocalizerConfig validated(LocalizerConfig c) {
  c.validate();
  return c;
}

}  // namespace

Localizer::Impl::Impl(const OccupancyGrid& grid, LocalizerConfig cfg)
    : config(validated(std::move(cfg))),
      map(grid),
      executor(config.threads),
      motion(make_motion(config)),

      selection{.max_beams = config.max_beams,
                .range_min = config.laser_min_range,
                .range_max = config.laser_max_range,
                .keep_max_range = config.laser_model_type == LaserModel::kBeam},
      kld(kld_of(config)),
      bins(map.bounds(), config.kld_bin_xy, config.kld_bin_xy, config.kld_bin_theta),
      recovery({config.recovery_alpha_slow, config.recovery_alpha_fast}),
      summarize(ClusterConfig{.bin_x = config.kld_bin_xy,
                              .bin_y = config.kld_bin_xy,
                              .bin_theta = config.kld_bin_theta}) {
  // The distance field / Embree scene are built in parallel on the Localizer's own threads.
  executor.run([&] { sensor = std::make_unique<SensorVariant>(make_sensor(map, config)); });
  store.reserve(static_cast<std::size_t>(config.max_particles));
}

bool Localizer::Impl::reject(UpdateOutcome outcome, std::string reason) {
  stats.outcome = outcome;
  stats.reason = std::move(reason);
  return false;
}

std::string Localizer::Impl::select(const LaserScan& scan) {
  select_beams(scan, selection, beams);
  stats.beams = beams.size();
  if (beams.empty()) return "no valid beam in the scan";
  // What the ray cast would refuse (ray_setup.cpp) is refused here, before motion has moved the
  // particles: update() must not throw half-way.
  if (!std::ranges::all_of(beams.angle, [](float a) { return std::isfinite(a); })) {
    return "scan beam angles (angle_min + i * angle_increment) overflow float";
  }
  if (config.laser_model_type == LaserModel::kBeam &&
      !(beams.range_max > 0.0F && std::isfinite(beams.range_max))) {
    return "scan range_max " + std::to_string(beams.range_max) +
           " m: the beam model needs a positive, finite maximum range (or set laser_max_range)";
  }
  return "";
}

bool Localizer::Impl::moved_enough(const Pose2& odometry) const {
  const Pose2 delta = between(last_odometry, odometry);
  return std::hypot(delta.x, delta.y) > config.update_min_d ||
         std::abs(delta.theta) > config.update_min_a;
}

bool Localizer::Impl::jumped(const Pose2& odometry) const {
  const Pose2 delta = between(last_odometry, odometry);
  return std::hypot(delta.x, delta.y) > config.odom_jump_max_d;
}

bool Localizer::Impl::reset_odometry(const Pose2& odometry) {
  const Pose2 delta = between(last_odometry, odometry);
  last_odometry = odometry;  // later steps count from here
  return reject(UpdateOutcome::kRejectedOdometry,
                "odometry jumped " + std::to_string(std::hypot(delta.x, delta.y)) +
                    " m since the last update (more than odom_jump_max_d): taken as an "
                    "odometry reset, particles kept");
}

std::string scan_geometry_problem(const LaserScan& scan) {
  if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment)) {
    return "scan beam angles are not finite (angle_min, angle_increment)";
  }
  if (std::isnan(scan.range_min) || std::isnan(scan.range_max)) {
    return "scan range_min or range_max is NaN";
  }
  if (!is_finite(scan.sensor_pose)) return "scan sensor pose is not finite";
  return "";
}

void Localizer::Impl::predict(const Pose2& odometry) {
  const Odometry u{last_odometry, odometry};
  std::visit(
      [&](const auto& model) {
        mote::predict(model, u, store.view(), config.seed, step, config.grain);
      },
      motion);
}

void Localizer::Impl::weigh() {
  stats.weighed = store.size();
  std::visit(
      [&](auto& model) {
        if constexpr (requires { model.prepare(beams); }) model.prepare(beams);
        weigh_scan(model, beams, store.view(), config.grain);
      },
      *sensor);
}

void Localizer::Impl::normalize() {
  // logw held log(w_prev) + log p(z | x) with sum(w_prev) = 1, so log_total is log of the
  // weighted mean likelihood: w_avg of Thrun table 8.3, line 8.
  const NormalizeResult result = mote::normalize(store.view(), config.grain);
  degenerate = !result.ok();
  stats.effective_sample_size = result.effective_sample_size;
  // Augmented MCL averages the likelihood per beam (the geometric mean over the scan's beams):
  // a 60-beam likelihood swings by e^5 between ordinary scans, which would make
  // 1 - w_fast / w_slow inject particles on every update. Per beam, only a real drop in how
  // well the map explains the scan moves the ratio.
  recovery.update(result.log_total / static_cast<double>(std::max<std::size_t>(beams.size(), 1)));
  stats.log_w_slow = recovery.log_w_slow();
  stats.log_w_fast = recovery.log_w_fast();
  if (degenerate) {
    stats.reason =
        "no particle explains the scan (every log-likelihood is -inf or NaN); "
        "weights reset to uniform";
  }
}

void Localizer::Impl::maybe_resample() {
  // Never resample without motion (the first scan after initialization): it would only lose
  // diversity (Thrun section 4.3.4).
  if (!has_odometry) return;
  if (++updates_since_resample < config.resample_interval) return;
  const double p_inject = recovery.injection_probability();
  const std::size_t n = store.size();
  if (!should_resample(stats.effective_sample_size, n, config.resample_ess_fraction) &&
      p_inject <= 0.0) {
    return;
  }
  updates_since_resample = 0;
  const std::size_t n_out = kld_sample_count(std::as_const(store).view(), bins, kld, config.grain);
  resample_systematic(store, n_out, config.seed, step, config.grain);
  stats.resampled = true;
  if (p_inject > 0.0) {
    stats.injected =
        inject_random_particles(store.view(), p_inject, map, config.seed, step, config.grain);
  }
}

void Localizer::Impl::update_estimate() {
  const ParticleSummary& summary = summarize(std::as_const(store).view());
  estimate.overall = summary.overall;
  estimate.clusters = summary.clusters;
  // Heaviest first; ties keep the deterministic order the summarizer gives.
  std::stable_sort(
      estimate.clusters.begin(), estimate.clusters.end(),
      [](const PoseEstimate& a, const PoseEstimate& b) { return a.weight > b.weight; });
}

}  // namespace mote
