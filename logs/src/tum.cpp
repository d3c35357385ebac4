/// \file
/// TUM trajectory reading and writing (format of Sturm et al., "A benchmark for the evaluation of
/// RGB-D SLAM systems", IROS 2012), and reference poses looked up by stamp.

#include "mote/logs/tum.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <istream>
#include <iterator>
#include <limits>
#include <ostream>

#include "mote/core/error.hpp"
#include "text_fields.hpp"

namespace mote::logs {

double yaw_from_quaternion(double qx, double qy, double qz, double qw) noexcept {
  // Z-Y-X Euler yaw of a unit quaternion; invariant to the quaternion's scale.
  return wrap_angle(std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz)));
}

namespace {

StampedPose parse_tum_line(detail::LineFields& f) {
  f.expect_remaining(8, "TUM pose (timestamp x y z qx qy qz qw)");
  StampedPose out;
  out.stamp = f.finite("timestamp");
  out.pose.x = f.finite("x");
  out.pose.y = f.finite("y");
  (void)f.finite("z");
  const double qx = f.finite("qx");
  const double qy = f.finite("qy");
  const double qz = f.finite("qz");
  const double qw = f.finite("qw");
  const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
  if (!(norm > 1e-9)) f.fail("quaternion has zero length");
  out.pose.theta = yaw_from_quaternion(qx / norm, qy / norm, qz / norm, qw / norm);
  return out;
}

}  // namespace

std::vector<StampedPose> read_tum(std::istream& in, const std::string& name) {
  std::vector<StampedPose> poses;
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    detail::LineFields fields(line, name, line_no);
    if (fields.empty() || fields.peek(0).front() == '#') continue;
    poses.push_back(parse_tum_line(fields));
  }
  const std::string end = "line " + std::to_string(line_no + 1);
  if (in.bad()) throw InputError(name, end, "read error");
  // A trajectory file without a single pose is empty or cut, never a meaningful reference.
  if (poses.empty()) throw InputError(name, end, "end of file without a pose");
  return poses;
}

std::vector<StampedPose> read_tum(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in || std::filesystem::is_directory(path)) {
    throw InputError(path.string(), "", "cannot open file");
  }
  return read_tum(in, path.string());
}

void write_tum(std::ostream& out, std::span<const StampedPose> poses) {
  char buffer[160];
  for (const StampedPose& p : poses) {
    // Rotation about z only: q = (0, 0, sin(theta/2), cos(theta/2)).
    const double half = 0.5 * p.pose.theta;
    const int n = std::snprintf(buffer, sizeof(buffer), "%.9f %.6f %.6f 0 0 0 %.9f %.9f\n", p.stamp,
                                p.pose.x, p.pose.y, std::sin(half), std::cos(half));
    if (n < 0 || static_cast<std::size_t>(n) >= sizeof(buffer)) {
      throw Error("write_tum: pose too large to format");
    }
    out.write(buffer, n);
  }
}

void write_tum(const std::filesystem::path& path, std::span<const StampedPose> poses) {
  std::ofstream out(path);
  if (!out) throw Error(path.string() + ": cannot open for writing");
  write_tum(out, poses);
  out.flush();
  if (!out) throw Error(path.string() + ": write failed");
}

std::vector<StampedPose> sort_by_stamp(std::span<const StampedPose> poses) {
  std::vector<StampedPose> sorted(poses.begin(), poses.end());
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
  return sorted;
}

std::optional<StampedPose> match_reference(std::span<const StampedPose> reference, double stamp,
                                           double tolerance) {
  const auto later = std::lower_bound(reference.begin(), reference.end(), stamp,
                                      [](const StampedPose& p, double t) { return p.stamp < t; });
  std::optional<StampedPose> best;
  double best_gap = std::numeric_limits<double>::infinity();
  const auto consider = [&](auto it) {
    const double gap = std::abs(it->stamp - stamp);
    if (gap <= tolerance && gap < best_gap) {
      best = *it;
      best_gap = gap;
    }
  };
  if (later != reference.end()) consider(later);
  if (later != reference.begin()) consider(std::prev(later));
  return best;
}

}  // namespace mote::logs
