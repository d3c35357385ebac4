// The reported pose while another place challenges the tracked one (hypothesis_hold.hpp).
#include <cmath>

#include "localizer_impl.hpp"

namespace mote {

void Localizer::Impl::hold_reported_place(const Pose2& odometry) {
  const Pose2 reported = estimate.refined.pose;
  if (!has_held) {
    // Nothing to hold before the belief has settled on tight hypotheses (a global search
    // reports its best until then); from there on, look-alike places do not swap the report.
    has_held = focused || stats.state == LocalizationState::kTracking;
    held = reported;
    return;
  }
  const Pose2 moved = between(last_odometry, odometry);
  const Pose2 carried = compose(held, moved);
  const double range = scan_range;
  if (endpoints.empty()) {  // no scale and no evidence: the report stays where it was
    held = hold.active() ? carried : reported;
    if (hold.active()) hold_report(ScanMatch{.pose = carried});
    return;
  }
  if (!HypothesisHold::other_place(carried, reported, range)) {
    hold.end();
    held = reported;
    return;
  }
  // Another place is the heaviest hypothesis: match the scan at the held place too, and let
  // this scan add its evidence between them.
  const ScanMatch there = matcher->match(endpoints, carried, correlation);
  const Pose2 at = there.converged ? there.pose : carried;
  if (!hold.active()) hold.challenge();
  // The challenger at its best fit too, where the gate refused its match.
  const Pose2 challenger = stats.refined_matched ? reported : fitted(reported);
  const HitDifference difference = matcher->hit_difference(endpoints, challenger, at);
  const double travelled = std::hypot(moved.x, moved.y) + std::abs(moved.theta) * range;
  if (hold.after_scan(difference, correlation, travelled, range)) {
    hold.end();
    held = reported;
    stats.switched = true;
    return;
  }
  held = at;
  hold_report(there.converged ? there
                              : ScanMatch{.pose = at,
                                          .endpoints = endpoints.size(),
                                          .hit_share = matcher->hit_share(endpoints, at)});
}

void Localizer::Impl::hold_report(const ScanMatch& at_held) {
  estimate.refined = at_held;
  stats.held = true;
  if (stats.state == LocalizationState::kTracking) stats.state = LocalizationState::kUncertain;
}

}  // namespace mote
