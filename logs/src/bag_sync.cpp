/// \file
/// Odometry interpolation and tf lookup for bag scans.

#include "bag_sync.hpp"

#include <algorithm>

namespace mote::logs::detail {
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
  if (!odom.child_frame_id.empty() && !fixed_base_) base_frame_ = odom.child_frame_id;
  if (!odom.frame_id.empty()) odom_frame_ = odom.frame_id;
  push_odometry(odom.stamp, odom.pose);
}

void ScanSync::add_transforms(const std::vector<TransformMessage>& transforms) {
  for (const TransformMessage& t : transforms) {
    links_[t.child] = {t.parent, t.pose, t.mirrored};
    if (t.parent == odom_frame_) {
      if (!fixed_base_ && (base_frame_.empty() || !from_topic_)) base_frame_ = t.child;
      if (!from_topic_ && t.child == base_frame_) push_odometry(t.stamp, t.pose);
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
  if (fixed_base_) return false;
  const auto it = links_.find(frame);
  return it != links_.end() && it->second.parent == odom_frame_;
}

std::optional<ScanSync::Mount> ScanSync::mount(const std::string& frame) const {
  Mount m;
  std::string current = frame;
  for (int step = 0; step < kMaxChain; ++step) {
    if (is_base(current)) return m;
    const auto it = links_.find(current);
    if (it == links_.end()) break;
    // A mirrored parent link (R M, t) with M = diag(1, -1) turns the child's (x, y, theta)
    // into (x, -y, -theta) before its rotation applies: M R(theta) = R(-theta) M.
    const Link& link = it->second;
    Pose2 below = m.pose;
    if (link.mirrored) below = {below.x, -below.y, -below.theta};
    m.pose = compose(link.pose, below);
    m.mirrored = m.mirrored != link.mirrored;
    current = link.parent;
  }
  return std::nullopt;
}

// Live: a scan that waited max_wait_ behind the newest one will not be used (the newest scan
// wins anyway), and odometry from before the oldest pending scan's bracket is never read again.
void ScanSync::drop_stale() {
  while (pending_.size() > 1 &&
         pending_.front().scan.stamp < pending_.back().scan.stamp - max_wait_) {
    if (mount(pending_.front().frame_id)) {
      ++dropped_.no_odometry;
    } else {
      ++dropped_.no_transform;
      dropped_.last_frame = pending_.front().frame_id;
    }
    pending_.pop_front();
  }
  const double keep_from =
      pending_.empty() ? (odom_.empty() ? 0.0 : odom_.back().stamp) : pending_.front().scan.stamp;
  while (odom_.size() > 2 && odom_[1].stamp <= keep_from) odom_.pop_front();
}

bool ScanSync::flush(std::deque<ScanFrame>& out, bool at_end) {
  if (live_) drop_stale();
  while (!pending_.empty()) {
    ScanMessage& scan = pending_.front();
    const double t = scan.scan.stamp;
    const std::optional<Mount> sensor = mount(scan.frame_id);
    if (!at_end) {
      if (odom_.empty() || odom_.back().stamp < t) return true;
      if (!sensor && odom_.back().stamp < t + kTransformWait) return true;
    }
    if (odom_.empty()) return false;
    if (live_ && !sensor) {
      ++dropped_.no_transform;
      dropped_.last_frame = scan.frame_id;
      pending_.pop_front();
      continue;
    }
    ScanFrame frame;
    frame.stamp = t;
    frame.odometry = odometry_at(t);
    frame.scan = std::move(scan.scan);
    const Mount m = sensor.value_or(Mount{});
    frame.scan.sensor_pose = m.pose;
    if (m.mirrored) {  // a laser mounted upside down sweeps the other way
      frame.scan.angle_min = -frame.scan.angle_min;
      frame.scan.angle_increment = -frame.scan.angle_increment;
    }
    out.push_back(std::move(frame));
    pending_.pop_front();
    while (odom_.size() > 2 && odom_[1].stamp <= t) odom_.pop_front();
  }
  return true;
}

}  // namespace mote::logs::detail
