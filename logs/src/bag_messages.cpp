/// \file
/// ROS message deserialization by hand (no ROS dependency).

#include "bag_messages.hpp"

#include <cmath>

#include "bag_format.hpp"
#include "laser_scan_fields.hpp"
#include "mote/logs/tum.hpp"

namespace mote::logs::detail {
namespace {

struct Header {
  double stamp = 0.0;
  std::string frame_id;
};

/// std_msgs/Header: uint32 seq, time stamp, string frame_id.
Header read_header(ByteReader& r) {
  Header h;
  (void)r.u32("header.seq");
  h.stamp = r.time("header.stamp");
  h.frame_id = normalize_frame(r.string("header.frame_id"));
  return h;
}

double finite(ByteReader& r, const char* what) {
  const std::size_t at = r.position();
  const double v = r.f64(what);
  if (!std::isfinite(v)) throw BagDecodeError{at, std::string(what) + ": expected a finite number"};
  return v;
}

/// geometry_msgs/Point or Vector3 then Quaternion, reduced to x, y, yaw.
Pose2 read_planar_pose(ByteReader& r) {
  Pose2 p;
  p.x = finite(r, "position.x");
  p.y = finite(r, "position.y");
  (void)finite(r, "position.z");
  const double qx = finite(r, "orientation.x");
  const double qy = finite(r, "orientation.y");
  const double qz = finite(r, "orientation.z");
  const double qw = finite(r, "orientation.w");
  if (!(qx * qx + qy * qy + qz * qz + qw * qw > 1e-12)) {
    throw BagDecodeError{r.position(), "quaternion has zero length"};
  }
  p.theta = yaw_from_quaternion(qx, qy, qz, qw);
  return p;
}

void expect_end(const ByteReader& r, const char* type) {
  if (r.remaining() != 0) {
    throw BagDecodeError{r.position(), std::string(type) + " has " + std::to_string(r.remaining()) +
                                           " trailing bytes"};
  }
}

}  // namespace

std::string normalize_frame(std::string_view frame) {
  while (!frame.empty() && frame.front() == '/') frame.remove_prefix(1);
  return std::string(frame);
}

ScanMessage decode_laser_scan(std::string_view bytes) {
  ByteReader r(bytes);
  ScanMessage m;
  const Header h = read_header(r);
  m.frame_id = h.frame_id;
  m.scan.stamp = h.stamp;
  read_laser_scan_fields(r, m.scan);
  expect_end(r, "LaserScan");
  return m;
}

OdometryMessage decode_odometry(std::string_view bytes) {
  ByteReader r(bytes);
  OdometryMessage m;
  const Header h = read_header(r);
  m.stamp = h.stamp;
  m.frame_id = h.frame_id;
  m.child_frame_id = normalize_frame(r.string("child_frame_id"));
  m.pose = read_planar_pose(r);
  (void)r.take(36 * 8, "pose.covariance");
  (void)r.take(6 * 8 + 36 * 8, "twist");
  expect_end(r, "Odometry");
  return m;
}

std::vector<TransformMessage> decode_tf(std::string_view bytes) {
  ByteReader r(bytes);
  const std::size_t at = r.position();
  const std::uint32_t n = r.u32("transforms length");
  constexpr std::size_t kMinTransformBytes = 16 + 4 + 7 * 8;
  if (n > r.remaining() / kMinTransformBytes) {
    throw BagDecodeError{at, "transforms length exceeds the message"};
  }
  std::vector<TransformMessage> out(n);
  for (TransformMessage& t : out) {
    const Header h = read_header(r);
    t.stamp = h.stamp;
    t.parent = h.frame_id;
    t.child = normalize_frame(r.string("child_frame_id"));
    t.pose = read_planar_pose(r);
  }
  expect_end(r, "TFMessage");
  return out;
}

}  // namespace mote::logs::detail
