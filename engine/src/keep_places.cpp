// Places that still explain the scans keep a share of the belief (localizer_impl.hpp,
// keep_places).
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <optional>

#include "blocked_beams.hpp"
#include "localizer_impl.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/weights.hpp"

namespace mote {
namespace {

// The share of the belief a place keeps while the scans favour no other place over it: what
// focused() counts as a hypothesis of its own.
constexpr double kPlaceFloor = 1.0 - BlockedBeamFilter::kFocusedWeight;
// A particle belongs to a cluster within this squared Mahalanobis distance of its mean: the
// 0.999 quantile of chi-square with 3 degrees of freedom.
constexpr double kMemberGate = 16.27;

// Whether pose p lies within the cluster's gate.
bool member(const PoseEstimate& c, const Eigen::Matrix3d& inverse, const Pose2& p) {
  const Eigen::Vector3d d(p.x - c.mean.x, p.y - c.mean.y, wrap_angle(p.theta - c.mean.theta));
  return d.dot(inverse * d) <= kMemberGate;
}

}  // namespace

bool Localizer::Impl::keep_place(const PoseEstimate& place) {
  Eigen::Matrix3d cov = place.covariance;
  cov.diagonal().array() += 1e-6;  // a cluster of identical particles
  const Eigen::Matrix3d inverse = cov.ldlt().solve(Eigen::Matrix3d::Identity());
  const ParticleView p = store.view();
  double inside = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (member(place, inverse, p.pose(i))) inside += std::exp(static_cast<double>(p.logw[i]));
  }
  if (!(inside > 0.0) || inside >= kPlaceFloor) return false;
  // Raise the place to the floor and scale the rest down: the weights stay normalized, and
  // within each part their ratios stay what the scans made them. A thousandth above the floor,
  // so that float rounding does not leave the place just under it, where neither the count of
  // places nor the next update's keep_places() would see it.
  const double target = kPlaceFloor * 1.001;
  const auto raise = static_cast<float>(std::log(target / inside));
  const auto lower = static_cast<float>(std::log((1.0 - target) / (1.0 - inside)));
  par::for_each_chunk(p.size(), config.grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      p.logw[i] += member(place, inverse, p.pose(i)) ? raise : lower;
    }
  });
  return true;
}

void Localizer::Impl::keep_places(const Pose2& odometry) {
  // The places of the previous update, carried by the odometry: a cluster at one of them that
  // fell below the floor is kept at it as long as this scan fits it as well as the best
  // hypothesis (McNemar's z between them not below -HypothesisHold::kZ).
  const Pose2 moved = between(last_odometry, odometry);
  const double range = mean_endpoint_range(readings);
  const std::vector<Pose2>& before = place_anchors;
  // Not before the belief has settled on tight hypotheses (as the hold): a global search's
  // clusters come and go with every scan, and holding them up at a tenth each kept Wean's
  // look-alike corridors in the belief until one of them won.
  if (!has_held || estimate.clusters.size() < 2 || endpoints.empty()) return;
  const PoseEstimate& best = estimate.clusters.front();
  // Each compared at its best fit to the scan: a cloud's mean lies a few centimetres and a
  // degree or two off, and at the hit band that alone loses dozens of readings.
  const auto fitted = [&](const Pose2& start) {
    const ScanMatch m = matcher->match(endpoints, start, correlation);
    return m.converged ? m.pose : start;
  };
  std::optional<Pose2> best_fit;
  bool changed = false;
  for (const PoseEstimate& c : estimate.clusters) {
    if (c.weight >= kPlaceFloor || !(c.weight > 0.0)) continue;
    if (!HypothesisHold::other_place(best.mean, c.mean, range)) continue;
    const bool known = std::any_of(before.begin(), before.end(), [&](const Pose2& a) {
      return !HypothesisHold::other_place(compose(a, moved), c.mean, range);
    });
    if (!known) continue;
    if (!best_fit) best_fit = fitted(best.mean);
    const HitDifference d = matcher->hit_difference(endpoints, fitted(c.mean), *best_fit);
    if (HypothesisHold::z(d, correlation) < -HypothesisHold::kZ) continue;
    changed = keep_place(c) || changed;
  }
  if (changed) update_estimate();
}

}  // namespace mote
