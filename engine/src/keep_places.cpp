// Places that still explain the scans keep a share of the belief (localizer_impl.hpp,
// keep_places).
#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <variant>

#include "blocked_beams.hpp"
#include "localizer_impl.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/weights.hpp"
#include "weight_sums.hpp"

namespace mote {
namespace {

// The share of the belief a place keeps while the scans favour no other place over it: what
// focused() counts as a hypothesis of its own.
constexpr double kPlaceFloor = 1.0 - BlockedBeamFilter::kFocusedWeight;
// The places the belief can hold at the floor each, the best among them.
constexpr auto kMaxPlaces = static_cast<std::size_t>(1.0 / kPlaceFloor + 0.5);
// A particle belongs to a cluster within this squared Mahalanobis distance of its mean: the
// 0.999 quantile of chi-square with 3 degrees of freedom.
constexpr double kMemberGate = 16.27;

// The gate of a cluster: its mean and the inverse of its covariance, as plain numbers (the
// weight sums run in kernels compiled per instruction set).
struct Gate {
  double x, y, theta;
  double a, b, c, d, e, f;  // inverse covariance: [a b c; b d e; c e f]

  explicit Gate(const PoseEstimate& cluster)
      : x(cluster.mean.x), y(cluster.mean.y), theta(cluster.mean.theta) {
    Eigen::Matrix3d cov = cluster.covariance;
    cov.diagonal().array() += 1e-6;  // a cluster of identical particles
    const Eigen::Matrix3d inv = cov.ldlt().solve(Eigen::Matrix3d::Identity());
    a = inv(0, 0), b = inv(0, 1), c = inv(0, 2), d = inv(1, 1), e = inv(1, 2), f = inv(2, 2);
  }
  [[nodiscard]] bool contains(const Pose2& p) const noexcept {
    const double u = p.x - x;
    const double v = p.y - y;
    const double w = wrap_angle(p.theta - theta);
    const double q = a * u * u + d * v * v + f * w * w + 2.0 * (b * u * v + c * u * w + e * v * w);
    return q <= kMemberGate;
  }
};

}  // namespace

bool Localizer::Impl::raise_places(const std::vector<const PoseEstimate*>& fallen) {
  std::vector<Gate> gates;
  for (const PoseEstimate* place : fallen) gates.emplace_back(*place);
  const ParticleView p = store.view();
  // The first gate a particle falls in (the places are a scan range apart, their gates rarely
  // overlap), or gates.size() for none.
  const auto gate_of = [&gates](const Pose2& pose) {
    return static_cast<std::size_t>(
        std::find_if(gates.begin(), gates.end(), [&](const Gate& g) { return g.contains(pose); }) -
        gates.begin());
  };
  // Each place's weight, summed in fixed blocks (the same for any thread count and grain), over
  // the particles whose first gate it is: the sums are disjoint where two gates overlap.
  std::vector<double> inside(gates.size());
  for (std::size_t k = 0; k < gates.size(); ++k) {
    inside[k] = detail::sum_weights(p.size(), 0.0F, [p, &gate_of, k](std::size_t i) {
                  return gate_of(p.pose(i)) == k ? p.logw[i] : detail::kNegInfF;
                }).w;
  }
  // Raise each place to the floor and scale the rest down: the weights stay normalized, and
  // within each part their ratios stay what the scans made them. A thousandth above the floor,
  // so that float rounding does not leave a place just under it, where neither the count of
  // places nor the next update's keep_places() would see it.
  const double target = kPlaceFloor * 1.001;
  std::vector<float> log_factor(gates.size() + 1, 0.0F);
  double raised = 0.0;
  double raised_to = 0.0;
  for (std::size_t k = 0; k < gates.size(); ++k) {
    if (!(inside[k] > 0.0) || inside[k] >= kPlaceFloor) continue;
    log_factor[k] = static_cast<float>(std::log(target / inside[k]));
    raised += inside[k];
    raised_to += target;
  }
  if (raised_to == 0.0 || raised_to >= 1.0) return false;
  log_factor.back() = static_cast<float>(std::log((1.0 - raised_to) / (1.0 - raised)));
  // Places left as they were (at or above the floor) are scaled with the rest.
  for (std::size_t k = 0; k < gates.size(); ++k) {
    if (!(inside[k] > 0.0) || inside[k] >= kPlaceFloor) log_factor[k] = log_factor.back();
  }
  par::for_each_chunk(p.size(), config.grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) p.logw[i] += log_factor[gate_of(p.pose(i))];
  });
  return true;
}

void Localizer::Impl::keep_places(const Pose2& odometry) {
  // The places of the previous update, carried by the odometry: the heaviest cluster at one of
  // them that fell below the floor (no cluster there holds it any more) is raised back to it,
  // as long as the scans have not refuted it against the best hypothesis (refuted()). Every
  // such place in one raise: raising one lowers every other, and two raises in turn undid each
  // other, while one place per update left a second place that fell in the same update without
  // particles (a map of 25 identical floors went from three places to one in two updates and
  // read tracking one floor over).
  // Not before the belief has settled on tight hypotheses (as the hold): a global search's
  // clusters come and go with every scan, and holding them up at a tenth each kept Wean's
  // look-alike corridors in the belief until one of them won.
  const Pose2 moved = between(last_odometry, odometry);
  if (!has_held || estimate.clusters.size() < 2 || endpoints.empty()) {
    forget_places(moved);
    return;
  }
  const PoseEstimate& best = estimate.clusters.front();
  const auto at = [&](const Pose2& place, const Pose2& pose) {
    return !HypothesisHold::other_place(place, pose, scan_range);
  };
  std::optional<BestFit> best_fit;          // matched once, when a place beside it needs it
  std::vector<const PoseEstimate*> judged;  // each cluster once, though two anchors reach it
  std::vector<const PoseEstimate*> fallen_places;
  std::size_t held_places = 1;  // the best
  for (const Pose2& anchor : place_anchors) {
    const Pose2 place = compose(anchor, moved);
    if (at(place, best.mean)) continue;
    // Clusters are heaviest first: the first one here is the place's.
    const auto here =
        std::find_if(estimate.clusters.begin(), estimate.clusters.end(),
                     [&](const PoseEstimate& c) { return at(place, c.mean) && c.weight > 0.0; });
    if (here == estimate.clusters.end()) continue;
    if (std::find(judged.begin(), judged.end(), &*here) != judged.end()) continue;
    judged.push_back(&*here);
    const bool fallen = here->weight < kPlaceFloor;
    if (!best_fit) best_fit = fit_best(best);
    if (refuted(*here, *best_fit, moved, fallen)) continue;
    if (fallen) {
      fallen_places.push_back(&*here);
    } else {
      ++held_places;
    }
  }
  // No more places at a tenth than the belief holds: the best and the places still above the
  // floor keep theirs (previous update's anchors come heaviest first).
  const std::size_t room = kMaxPlaces - std::min(held_places, kMaxPlaces);
  if (fallen_places.size() > room) fallen_places.resize(room);
  forget_places(moved);
  if (!fallen_places.empty() && raise_places(fallen_places)) update_estimate();
}

Localizer::Impl::BestFit Localizer::Impl::fit_best(const PoseEstimate& best) const {
  const Pose2 pose = fitted(best.mean);
  return {.pose = pose, .log_likelihood = scan_log_likelihood(pose)};
}

bool Localizer::Impl::refuted(const PoseEstimate& place, const BestFit& best, const Pose2& moved,
                              bool fallen) {
  const auto same = [&](const PlaceEvidence& e) {
    return !HypothesisHold::other_place(compose(e.place, moved), place.mean, scan_range);
  };
  auto it = std::find_if(place_evidence.begin(), place_evidence.end(), same);
  if (it == place_evidence.end()) it = place_evidence.emplace(place_evidence.end());
  PlaceEvidence& e = *it;
  e.place = place.mean;
  e.seen = true;
  if (e.refuted) return true;
  const Pose2 here = fitted(place.mean);
  // A fallen place, on this scan alone: McNemar's z on the readings that hit the map at one of
  // the two only (the hold's statistic, at one look's level).
  if (fallen && HypothesisHold::z(matcher->hit_difference(endpoints, here, best.pose),
                                  correlation) < -HypothesisHold::kZ) {
    return e.refuted = true;
  }
  // Every scan since the place first stood beside the best: the sum of their log likelihood
  // ratios at the two fits, tempered as the particles' weights were (the filter's own measure
  // of evidence: the readings of a scan are not independent, kVeryStrongEvidence). Each ratio
  // is the sensor model's own at the place's best fit, so it has none of the particles' luck:
  // identical places give 0 scan after scan, and a place the scans keep disfavouring adds up. A
  // corridor's look-alike stretch 5 m along (Wean) fell by a factor of 2-10 per scan while no
  // reading told it apart.
  const double ratio = stats.tempering * (scan_log_likelihood(here) - best.log_likelihood);
  if (ratio == -INFINITY) return e.refuted = true;  // no pose there explains a reading
  if (std::isfinite(ratio)) e.log_ratio += ratio;   // NaN (neither explains one): no evidence
  return e.refuted = e.log_ratio < kVeryStrongEvidence;
}

void Localizer::Impl::forget_places(const Pose2& moved) {
  // The evidence against a place lasts while it stands beside the best place; once it is the
  // best, or no anchor led to it (it starved away), it starts over. A refuted place stays
  // refuted while any of the belief is there: it starves away, drawn by its weight.
  const auto at_best = [&](const Pose2& place) {
    return !estimate.clusters.empty() &&
           !HypothesisHold::other_place(place, estimate.clusters.front().mean, scan_range);
  };
  std::erase_if(place_evidence, [&](PlaceEvidence& e) {
    if (!e.seen) e.place = compose(e.place, moved);  // not judged this update: carried
    const bool seen = std::exchange(e.seen, false);
    const bool in_belief =
        std::any_of(estimate.clusters.begin(), estimate.clusters.end(), [&](const PoseEstimate& c) {
          return c.weight > 0.0 && !HypothesisHold::other_place(e.place, c.mean, scan_range);
        });
    return at_best(e.place) || !(seen || (e.refuted && in_belief));
  });
}

double Localizer::Impl::scan_log_likelihood(const Pose2& pose) const {
  // One pose weighed as weigh() weighed the particles (the model is prepared for this scan's
  // beams), in a padded block of its own: the kernels run whole blocks of lanes.
  alignas(64) std::array<float, kParticlePadding> x{};
  alignas(64) std::array<float, kParticlePadding> y{};
  alignas(64) std::array<float, kParticlePadding> theta{};
  alignas(64) std::array<float, kParticlePadding> logw{};
  x.fill(static_cast<float>(pose.x));
  y.fill(static_cast<float>(pose.y));
  theta.fill(static_cast<float>(wrap_angle(pose.theta)));
  const ParticleView one{x.data(), y.data(), theta.data(), logw.data(), 1};
  if (beams.empty()) return 0.0;
  std::visit([&](const auto& model) { model.weigh(beams, one, 0, 1); }, *sensor);
  return static_cast<double>(logw[0]);
}

Pose2 Localizer::Impl::fitted(const Pose2& start) const {
  // A cloud's mean lies a few centimetres and a degree or two off, and at the hit band that
  // alone loses dozens of readings: places are compared at their best fit to the scan.
  const ScanMatch m = matcher->match(endpoints, start, correlation);
  return m.converged ? m.pose : start;
}

}  // namespace mote
