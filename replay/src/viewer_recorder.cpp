// The viewer's per-update recording: decimated particles with weights and the scan endpoints
// from the estimate, in 16-bit fixed point. Costs O(kViewerParticles + beams) per update.
#include <algorithm>
#include <cmath>
#include <limits>

#include "mote/replay/viewer.hpp"

namespace mote::replay {
namespace {

constexpr double kFixedMax = 65535.0;

std::uint16_t to_fixed(double value) {
  return static_cast<std::uint16_t>(std::lround(std::clamp(value, 0.0, kFixedMax)));
}

std::uint32_t to_u32(std::size_t n) { return static_cast<std::uint32_t>(n); }

}  // namespace

FixedPointGrid::FixedPointGrid(const OccupancyGrid& map)
    : origin_(map.origin()),
      cos_yaw_(std::cos(map.origin().theta)),
      sin_yaw_(std::sin(map.origin().theta)),
      resolution_(map.resolution()),
      width_(map.width()),
      height_(map.height()),
      per_cell_(kFixedMax / std::max({map.width(), map.height(), 1})) {}

// OccupancyGrid::to_grid_frame, in cells.
Point2 FixedPointGrid::cells(Point2 world) const noexcept {
  const double dx = world.x - origin_.x;
  const double dy = world.y - origin_.y;
  return {(cos_yaw_ * dx + sin_yaw_ * dy) / resolution_,
          (-sin_yaw_ * dx + cos_yaw_ * dy) / resolution_};
}

bool FixedPointGrid::inside(Point2 world) const noexcept {
  const Point2 c = cells(world);
  return c.x >= 0.0 && c.y >= 0.0 && c.x <= width_ && c.y <= height_;
}

std::uint16_t FixedPointGrid::u(Point2 world) const noexcept {
  const double c = cells(world).x * per_cell_;
  return to_fixed(std::isfinite(c) ? c : 0.0);
}

std::uint16_t FixedPointGrid::v(Point2 world) const noexcept {
  const double c = cells(world).y * per_cell_;
  return to_fixed(std::isfinite(c) ? c : 0.0);
}

void ViewerRecorder::record(const Localizer& filter, const ScanFrame& frame) {
  record_particles(filter.particles());
  const LocalizationEstimate& estimate = filter.estimate();
  record_endpoints(estimate.best().mean, frame.scan);
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
    const Point2 p{c.mean.x, c.mean.y};
    recording_.heavy_clusters.insert(recording_.heavy_clusters.end(),
                                     {grid_.u(p), grid_.v(p), to_fixed(c.weight * kFixedMax)});
  }
  recording_.heavy_cluster_end.push_back(to_u32(recording_.heavy_clusters.size()));
}

// An even stride over the set: resampling keeps the particles of one ancestor together, so a
// stride sees every part of the cloud in proportion to its particle count.
void ViewerRecorder::record_particles(const ConstParticleView& particles) {
  const std::size_t n = particles.size();
  const std::size_t kept = std::min(n, kViewerParticles);
  logw_.resize(kept);
  float max_logw = -std::numeric_limits<float>::infinity();
  for (std::size_t k = 0; k < kept; ++k) {
    logw_[k] = particles.logw[k * n / kept];
    if (std::isfinite(logw_[k])) max_logw = std::max(max_logw, logw_[k]);
  }
  for (std::size_t k = 0; k < kept; ++k) {
    const std::size_t i = k * n / kept;
    const Point2 p{particles.x[i], particles.y[i]};
    // Weights relative to the heaviest recorded particle: what the page's shading needs.
    const double w = std::isfinite(logw_[k]) ? std::exp(double{logw_[k]} - max_logw) : 0.0;
    recording_.particles.insert(recording_.particles.end(),
                                {grid_.u(p), grid_.v(p), to_fixed(w * kFixedMax)});
  }
  recording_.particle_end.push_back(to_u32(recording_.particles.size()));
}

// Endpoints of the valid beams (range_min <= r < range_max) cast from the estimate through the
// sensor's mounting pose; those that leave the map are left out.
void ViewerRecorder::record_endpoints(const Pose2& estimate, const LaserScan& scan) {
  const Pose2 sensor = compose(estimate, scan.sensor_pose);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const float r = scan.ranges[i];
    if (!(r >= scan.range_min && r < scan.range_max)) continue;
    const double a = sensor.theta + scan.beam_angle(i);
    const Point2 p{sensor.x + r * std::cos(a), sensor.y + r * std::sin(a)};
    if (!grid_.inside(p)) continue;
    recording_.endpoints.insert(recording_.endpoints.end(), {grid_.u(p), grid_.v(p)});
  }
  recording_.endpoint_end.push_back(to_u32(recording_.endpoints.size()));
}

}  // namespace mote::replay
