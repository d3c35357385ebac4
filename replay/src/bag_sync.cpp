/// \file
/// Odometry interpolation and tf lookup for bag scans.

#include "bag_sync.hpp"

#include <algorithm>

namespace mote::replay::detail {
namespace {

/// Seconds a scan waits for its laser transform before it is paired without one.
constexpr double kTransformWait = 1.0;
/// Longest chain base -> ... -> laser followed; guards against cycles in corrupt tf data.
constexpr int kMaxChain = 16;

Pose2 interpolate(const Pose2& a, const Pose2& b, double s) {
  return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y),
          wrap_angle(a.theta + s * wrap_angle(b.theta - a.theta))};
}

}  // namespace

void ScanSync::add_odometry(const OdometryMessage& odom) {
  if (!odom.child_frame_id.empty()) base_frame_ = odom.child_frame_id;
  if (!odom.frame_id.empty()) odom_frame_ = odom.frame_id;
  push_odometry(odom.stamp, odom.pose);
}

void ScanSync::add_transforms(const std::vector<TransformMessage>& transforms) {
  for (const TransformMessage& t : transforms) {
    links_[t.child] = {t.parent, t.pose};
    if (t.parent == odom_frame_) {
      if (base_frame_.empty() || !from_topic_) base_frame_ = t.child;
      if (!from_topic_) push_odometry(t.stamp, t.pose);
    }
  }
}

void ScanSync::push_odometry(double stamp, const Pose2& pose) {
  // Messages are time-sorted within a chunk; keep the history sorted if chunks overlap.
  const auto at = std::upper_bound(odom_.begin(), odom_.end(), stamp,
                                   [](double s, const Stamped& e) { return s < e.stamp; });
  odom_.insert(at, Stamped{stamp, pose});
}

Pose2 ScanSync::odometry_at(double stamp) const {
  const auto after = std::lower_bound(odom_.begin(), odom_.end(), stamp,
                                      [](const Stamped& e, double s) { return e.stamp < s; });
  if (after == odom_.begin()) return after->pose;
  if (after == odom_.end()) return odom_.back().pose;
  const Stamped& a = *(after - 1);
  const double span = after->stamp - a.stamp;
  return span > 0.0 ? interpolate(a.pose, after->pose, (stamp - a.stamp) / span) : after->pose;
}

bool ScanSync::is_base(const std::string& frame) const {
  if (frame == base_frame_) return true;
  const auto it = links_.find(frame);
  return it != links_.end() && it->second.parent == odom_frame_;
}

std::optional<Pose2> ScanSync::mount(const std::string& frame) const {
  Pose2 pose;
  std::string current = frame;
  for (int step = 0; step < kMaxChain; ++step) {
    if (is_base(current)) return pose;
    const auto it = links_.find(current);
    if (it == links_.end()) break;
    pose = compose(it->second.pose, pose);
    current = it->second.parent;
  }
  return std::nullopt;
}

bool ScanSync::flush(std::deque<ScanFrame>& out, bool at_end) {
  while (!pending_.empty()) {
    ScanMessage& scan = pending_.front();
    const double t = scan.scan.stamp;
    const std::optional<Pose2> sensor = mount(scan.frame_id);
    if (!at_end) {
      if (odom_.empty() || odom_.back().stamp < t) return true;
      if (!sensor && odom_.back().stamp < t + kTransformWait) return true;
    }
    if (odom_.empty()) return false;
    ScanFrame frame;
    frame.stamp = t;
    frame.odometry = odometry_at(t);
    frame.scan = std::move(scan.scan);
    frame.scan.sensor_pose = sensor.value_or(Pose2{});
    out.push_back(std::move(frame));
    pending_.pop_front();
    while (odom_.size() > 2 && odom_[1].stamp <= t) odom_.pop_front();
  }
  return true;
}

}  // namespace mote::replay::detail
