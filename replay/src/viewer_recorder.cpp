// The viewer's per-update recording: decimated particles with weights and the scan endpoints
// from the estimate, in 16-bit fixed point. Costs O(kViewerParticles + beams) per update.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "mote/replay/viewer.hpp"

namespace mote::replay {
namespace {

constexpr double kFixedMax = 65535.0;

std::uint32_t to_u32(std::size_t n) { return static_cast<std::uint32_t>(n); }

}  // namespace

FixedPointGrid::FixedPointGrid(const OccupancyGrid& map)
    : origin_(map.origin()),
      cos_yaw_(std::cos(map.origin().theta)),
      sin_yaw_(std::sin(map.origin().theta)),
      resolution_(map.resolution()),
      width_(map.width()),
      height_(map.height()),
      per_cell_(kFixedMax / std::max({map.width(), map.height(), 1})),
      cos_scaled_(cos_yaw_ * per_cell_ / resolution_),
      sin_scaled_(sin_yaw_ * per_cell_ / resolution_) {}

void ViewerRecorder::record(const Localizer& filter, const logs::ScanFrame& frame) {
  record_particles(filter.particles());
  const LocalizationEstimate& estimate = filter.estimate();
  record_endpoints(estimate.refined.pose, frame.scan);  // the reported pose
  record_clusters(estimate);
}

// The count and the heaviest few (estimate.clusters is heaviest first; none: the whole set).
void ViewerRecorder::record_clusters(const LocalizationEstimate& estimate) {
  const std::size_t clusters = std::max<std::size_t>(estimate.clusters.size(), 1);
  recording_.clusters.push_back(
      static_cast<std::uint16_t>(std::min<std::size_t>(clusters, UINT16_MAX)));
  const std::size_t kept = std::min(estimate.clusters.size(), kViewerClusters);
  for (std::size_t k = 0; k < std::max<std::size_t>(kept, 1); ++k) {
    const PoseEstimate& c = kept == 0 ? estimate.overall : estimate.clusters[k];
    const auto [u, v] = grid_.fixed({c.mean.x, c.mean.y});
    recording_.heavy_clusters.insert(recording_.heavy_clusters.end(),
                                     {u, v, to_fixed_point(c.weight * kFixedMax)});
  }
  recording_.heavy_cluster_end.push_back(to_u32(recording_.heavy_clusters.size()));
}

// An even stride over the set: systematic resampling (Thrun table 4.4, resample.hpp) writes the
// copies of one ancestor next to each other in ancestor order, so a stride sees every part of
// the cloud in proportion to its particle count. One pass writes the
// positions and keeps the log-weights; the second turns them into weights relative to the
// heaviest recorded particle, what the page's shading needs.
void ViewerRecorder::record_particles(const ConstParticleView& particles) {
  const std::size_t n = particles.size();
  const std::size_t kept = std::min(n, kViewerParticles);
  const double stride = kept > 0 ? static_cast<double>(n) / static_cast<double>(kept) : 0.0;
  const std::size_t begin = recording_.particles.size();
  if (recording_.particles.capacity() < begin + 3 * kept) {
    // Room for 1024 more updates at a time: no copy of the whole recording every few updates.
    recording_.particles.reserve(begin + 3 * kViewerParticles * 1024);
  }
  recording_.particles.resize(begin + 3 * kept);
  logw_.resize(kept);
  std::uint16_t* out = recording_.particles.data() + begin;
  float max_logw = -std::numeric_limits<float>::infinity();
  for (std::size_t k = 0; k < kept; ++k) {
    const std::size_t i =
        std::min(static_cast<std::size_t>(static_cast<double>(k) * stride), n - 1);
    const auto [u, v] = grid_.fixed({particles.x[i], particles.y[i]});
    out[3 * k] = u;
    out[3 * k + 1] = v;
    logw_[k] = particles.logw[i];
    if (std::isfinite(logw_[k])) max_logw = std::max(max_logw, logw_[k]);
  }
  // Below e^-12 a weight rounds to 0 of 65535 anyway; leaving exp() out there also keeps it from
  // the slow subnormal results of the far tail.
  constexpr float kNegligible = -12.0F;
  for (std::size_t k = 0; k < kept; ++k) {
    const float log_ratio = logw_[k] - max_logw;  // NaN for a non-finite log-weight
    const float w = log_ratio > kNegligible ? std::exp(log_ratio) : 0.0F;
    out[3 * k + 2] = to_fixed_point(double{w} * kFixedMax);
  }
  recording_.particle_end.push_back(to_u32(recording_.particles.size()));
}

// Endpoints of the valid beams (range_min <= r < range_max) cast from the estimate through the
// sensor's mounting pose; those that leave the map are left out.
void ViewerRecorder::record_endpoints(const Pose2& estimate, const LaserScan& scan) {
  const Pose2 sensor = compose(estimate, scan.sensor_pose);
  // The beam direction turned by angle_increment per beam (a rotation, not a cos and sin each).
  const double first = sensor.theta + scan.beam_angle(0);
  double c = std::cos(first), s = std::sin(first);
  const double dc = std::cos(double{scan.angle_increment});
  const double ds = std::sin(double{scan.angle_increment});
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const float r = scan.ranges[i];
    const Point2 p{sensor.x + r * c, sensor.y + r * s};
    const double turned = c * dc - s * ds;
    s = s * dc + c * ds;
    c = turned;
    if (!(r >= scan.range_min && r < scan.range_max) || !grid_.inside(p)) continue;
    const auto [u, v] = grid_.fixed(p);
    recording_.endpoints.insert(recording_.endpoints.end(), {u, v});
  }
  recording_.endpoint_end.push_back(to_u32(recording_.endpoints.size()));
}

}  // namespace mote::replay
