// The no-return value of a laser inferred from its scans (see no_return.hpp for the rule).
#include "mote/logs/no_return.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace mote::logs {

void NoReturnEstimator::add(std::span<const float> ranges, const Pose2& odometry) {
  if (any_ && odometry == last_odometry_) return;
  float top = 0.0F;
  for (const float r : ranges) {
    if (std::isfinite(r) && r > top) top = r;
  }
  if (top <= 0.0F) return;
  any_ = true;
  last_odometry_ = odometry;
  ++scans_;
  ++scans_topped_by_[top];
}

NoReturnRange NoReturnEstimator::estimate() const {
  NoReturnRange out;
  out.scans = scans_;
  if (scans_topped_by_.empty()) return out;
  const auto need = std::max<std::size_t>(2, (scans_ + 99) / 100);  // ceil(1 %)
  std::size_t above = 0;  // counted scans whose largest reading exceeds the candidate
  for (auto it = scans_topped_by_.rbegin(); it != scans_topped_by_.rend(); ++it) {
    const auto [value, count] = *it;
    if (count >= need && 4 * above <= count) {
      out.range_max = value;
      out.repeated = true;
      out.scans_at_max = count;
      return out;
    }
    above += count;
    if (4 * above > scans_) break;  // no lower value can be topped by few enough
  }
  out.range_max = scans_topped_by_.rbegin()->first * 1.01F;
  out.scans_at_max = 0;
  return out;
}

std::string NoReturnRange::describe() const {
  std::ostringstream s;
  if (repeated) {
    s << "inferred from the log: the largest reading of " << scans_at_max << " of the first "
      << scans << " moving scans";
  } else if (scans > 0) {
    s << "inferred from the log: no repeated top value in the first " << scans
      << " moving scans, so their largest reading + 1 %";
  } else {
    s << "no scan to infer it from";
  }
  return s.str();
}

}  // namespace mote::logs
