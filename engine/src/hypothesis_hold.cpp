#include "mote/engine/hypothesis_hold.hpp"

#include <algorithm>
#include <cmath>

#include "mote/engine/kld.hpp"

namespace mote {

bool HypothesisHold::other_place(const Pose2& a, const Pose2& b, double range) noexcept {
  const double shift =
      std::hypot(b.x - a.x, b.y - a.y) + std::abs(wrap_angle(b.theta - a.theta)) * range;
  return !(shift <= range);  // NaN poses are other places
}

double HypothesisHold::z(const HitDifference& d, double correlation) noexcept {
  const double discordant = static_cast<double>(d.only_challenger + d.only_held);
  if (discordant == 0.0) return 0.0;
  // Correlated readings: the counts carry the information of counts / correlation independent
  // ones, and the statistic scales with the square root of the count.
  return (static_cast<double>(d.only_challenger) - static_cast<double>(d.only_held)) /
         std::sqrt(discordant * std::max(1.0, correlation));
}

bool HypothesisHold::after_scan(const HitDifference& d, double correlation, double travelled,
                                double range) {
  sum_.only_challenger += d.only_challenger;
  sum_.only_held += d.only_held;
  // The travel since the first scan of the challenge: the motion before it saw no evidence.
  if (scans_ > 0) travelled_ += std::max(0.0, travelled);
  ++scans_;
  const double evidence = z(sum_, correlation);
  const double bound = boundary(scans_);
  if (evidence < -bound) {
    challenge();  // the held place explained the scans better: start over
    return false;
  }
  return evidence > bound && scans_ >= kMinScans && travelled_ >= range;
}

double HypothesisHold::boundary(int n) {
  const double looks = static_cast<double>(std::max(1, n));
  return standard_normal_quantile(1.0 - kAlpha / (looks * (looks + 1.0)));
}

}  // namespace mote
