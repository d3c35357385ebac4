/// \file
/// CDR decoders for LaserScan, Odometry, TFMessage and PoseWithCovarianceStamped, following the
/// .msg definitions of ROS 2 (sensor_msgs, nav_msgs, tf2_msgs, geometry_msgs; Humble).

#include "ros2_messages.hpp"

#include <array>
#include <cmath>

#include "cdr.hpp"
#include "laser_scan_fields.hpp"
#include "mote/logs/tum.hpp"

namespace mote::logs::detail {
namespace {

struct Header {
  double stamp = 0.0;
  std::string frame_id;
};

/// std_msgs/msg/Header: builtin_interfaces/Time stamp (int32 sec, uint32 nanosec), frame_id.
Header read_header(CdrReader& r) {
  Header h;
  const std::int32_t sec = r.i32("header.stamp.sec");
  const std::uint32_t nsec = r.u32("header.stamp.nanosec");
  h.stamp = static_cast<double>(sec) + 1e-9 * static_cast<double>(nsec);
  h.frame_id = normalize_frame(r.string("header.frame_id"));
  return h;
}

double finite(CdrReader& r, const char* what) {
  const std::size_t at = r.position();
  const double v = r.f64(what);
  if (!std::isfinite(v)) throw BagDecodeError{at, std::string(what) + ": expected a finite number"};
  return v;
}

/// Point/Vector3 then Quaternion, reduced to x, y, yaw and whether the child's z axis points
/// down (a sensor mounted upside down: its beam angles are mirrored in the parent frame).
TransformMessage read_transform(CdrReader& r) {
  TransformMessage t;
  t.pose.x = finite(r, "position.x");
  t.pose.y = finite(r, "position.y");
  (void)finite(r, "position.z");
  std::array<double, 4> q{};
  for (double& c : q) c = finite(r, "orientation");
  const auto [qx, qy, qz, qw] = q;
  const double norm2 = qx * qx + qy * qy + qz * qz + qw * qw;
  if (!(norm2 > 1e-12)) throw BagDecodeError{r.position(), "quaternion has zero length"};
  // Rotation matrix entries (R00, R10) give the planar heading of the child's x axis for any
  // roll and pitch; R22 < 0 means the child's z axis points down (roll or pitch of pi).
  t.pose.theta = yaw_from_quaternion(qx, qy, qz, qw);
  t.mirrored = 1.0 - 2.0 * (qx * qx + qy * qy) / norm2 < 0.0;
  return t;
}

}  // namespace

ScanMessage decode_laser_scan_cdr(std::string_view bytes) {
  CdrReader r(bytes);
  ScanMessage m;
  const Header h = read_header(r);
  m.frame_id = h.frame_id;
  m.scan.stamp = h.stamp;
  read_laser_scan_fields(r, m.scan);
  r.expect_end("LaserScan");
  return m;
}

OdometryMessage decode_odometry_cdr(std::string_view bytes) {
  CdrReader r(bytes);
  OdometryMessage m;
  const Header h = read_header(r);
  m.stamp = h.stamp;
  m.frame_id = h.frame_id;
  m.child_frame_id = normalize_frame(r.string("child_frame_id"));
  m.pose = read_transform(r).pose;
  r.skip(36, 8, "pose.covariance");
  r.skip(6 + 36, 8, "twist");
  r.expect_end("Odometry");
  return m;
}

std::vector<TransformMessage> decode_tf_cdr(std::string_view bytes) {
  CdrReader r(bytes);
  // A TransformStamped takes at least 8 (stamp) + 4 + 1 + 4 + 1 (two strings) + 7 * 8 bytes.
  constexpr std::size_t kMinTransformBytes = 8 + 10 + 56;
  std::vector<TransformMessage> out(r.sequence("transforms", kMinTransformBytes));
  for (TransformMessage& t : out) {
    const Header h = read_header(r);
    const std::string child = normalize_frame(r.string("child_frame_id"));
    t = read_transform(r);
    t.stamp = h.stamp;
    t.parent = h.frame_id;
    t.child = child;
  }
  r.expect_end("TFMessage");
  return out;
}

PoseMessage decode_pose_cdr(std::string_view bytes) {
  CdrReader r(bytes);
  PoseMessage m;
  const Header h = read_header(r);
  m.stamp = h.stamp;
  m.frame_id = h.frame_id;
  m.pose = read_transform(r).pose;
  for (double& c : m.covariance) c = r.f64("pose.covariance");
  r.expect_end("PoseWithCovarianceStamped");
  return m;
}

}  // namespace mote::logs::detail
