#pragma once
/// \file
/// `mote replay --viewer`: DIR/viewer.html, one self-contained page (plain HTML, CSS and
/// JavaScript, no network) that replays the filter over the map: per update the particles, the
/// scan endpoints from the estimate, the estimate and the reference so far, and timelines of the
/// update's statistics. The ViewerRecorder keeps what the page needs after each update, small
/// enough for a whole log (Intel, 910 updates: 5.6 MB of page with the defaults, 16.3 MB with
/// more than kViewerParticles particles at every update; the bound is 20 MB): positions in
/// 16-bit fixed point of the map's extent, at most kViewerParticles particles per update.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <vector>

#include "mote/core/free_space.hpp"
#include "mote/core/pose.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/replay/replay_run.hpp"

namespace mote::replay {

/// Most particles recorded per update: larger sets are decimated to an even stride.
inline constexpr std::size_t kViewerParticles = 2000;
/// Most clusters whose means are recorded per update (the heaviest).
inline constexpr std::size_t kViewerClusters = 8;
/// m: how far the map embedded in the page reaches beyond everything the page draws (the
/// estimate and reference, particles, scan endpoints, cluster means); the rest is cut off.
inline constexpr double kViewerMarginM = 1.0;

/// A value rounded to 16 bits: clamped to [0, 65535], NaN gives 0.
[[nodiscard]] inline std::uint16_t to_fixed_point(double value) noexcept {
  constexpr double kMax = 65535.0;
  if (!(value > 0.0)) return 0;
  if (value >= kMax) return UINT16_MAX;
  return static_cast<std::uint16_t>(value + 0.5);
}

/// Map frame positions to 16-bit fixed point: grid-frame cells times `per_cell`, where
/// per_cell = 65535 / max(width, height) so that the whole map fits in [0, 65535]. Keeps the
/// map's geometry by value (not the map). Inline: the recorder calls it for every particle.
class FixedPointGrid {
 public:
  explicit FixedPointGrid(const OccupancyGrid& map);
  /// Fixed-point units per map cell.
  [[nodiscard]] double per_cell() const noexcept { return per_cell_; }
  /// The point in grid-frame cells (column u from the left, row v from the bottom), as
  /// OccupancyGrid::to_grid_frame divided by the resolution.
  [[nodiscard]] Point2 cells(Point2 world) const noexcept {
    const double dx = world.x - origin_.x;
    const double dy = world.y - origin_.y;
    return {(cos_yaw_ * dx + sin_yaw_ * dy) / resolution_,
            (-sin_yaw_ * dx + cos_yaw_ * dy) / resolution_};
  }
  /// Whether `world` lies inside the map's extent (and is finite).
  [[nodiscard]] bool inside(Point2 world) const noexcept {
    const Point2 c = cells(world);
    return c.x >= 0.0 && c.y >= 0.0 && c.x <= width_ && c.y <= height_;
  }
  /// Fixed-point u and v of a point inside the map; clamped to the extent when outside, 0 for
  /// NaN.
  [[nodiscard]] std::array<std::uint16_t, 2> fixed(Point2 world) const noexcept {
    const double dx = world.x - origin_.x;
    const double dy = world.y - origin_.y;
    return {to_fixed_point(cos_scaled_ * dx + sin_scaled_ * dy),
            to_fixed_point(cos_scaled_ * dy - sin_scaled_ * dx)};
  }

 private:
  Pose2 origin_;
  double cos_yaw_, sin_yaw_, resolution_;
  int width_, height_;
  double per_cell_;
  double cos_scaled_, sin_scaled_;  // cos and sin of the yaw times per_cell / resolution
};

/// What the viewer shows of each update beyond ReplayResult::updates and ::trajectory (index k
/// of each column range belongs to the k-th update that ran).
struct ViewerRecording {
  /// Particles: u, v, weight per particle, weight = 65535 * w / max w of the recorded ones.
  std::vector<std::uint16_t> particles;
  std::vector<std::uint32_t> particle_end;  ///< per update: end of its triples in `particles`
  std::vector<std::uint16_t> endpoints;     ///< scan endpoints from the estimate: u, v pairs
  std::vector<std::uint32_t> endpoint_end;  ///< per update: end of its pairs in `endpoints`
  std::vector<std::uint16_t> clusters;      ///< per update: clusters of the estimate
  /// The kViewerClusters heaviest clusters' means and weights: u, v, 65535 * weight per
  /// cluster, heaviest first, fewer when there are fewer clusters.
  std::vector<std::uint16_t> heavy_clusters;
  std::vector<std::uint32_t> heavy_cluster_end;  ///< per update: end of its triples
};

/// Collects a ViewerRecording; pass record() as ReplayOptions::on_update.
class ViewerRecorder {
 public:
  explicit ViewerRecorder(const OccupancyGrid& map) : grid_(map) {}
  /// Records the filter's state after an update that ran on `frame`.
  void record(const Localizer& filter, const logs::ScanFrame& frame);
  [[nodiscard]] const ViewerRecording& recording() const noexcept { return recording_; }

 private:
  void record_particles(const ConstParticleView& particles);
  void record_endpoints(const Pose2& estimate, const LaserScan& scan);
  void record_clusters(const LocalizationEstimate& estimate);

  FixedPointGrid grid_;
  ViewerRecording recording_;
  std::vector<float> logw_;  // scratch: log-weights of the recorded particles
};

/// Writes the page for `result` and its recording (one entry per update) to `out`, with the
/// part of the map the run visits (kViewerMarginM). Throws mote::Error when the recording does
/// not belong to the result.
void write_viewer_page(std::ostream& out, const ReplayResult& result,
                       const ViewerRecording& recording);

/// write_viewer_page into `path`. Throws mote::Error naming the file when it cannot be written.
void write_viewer_html(const std::filesystem::path& path, const ReplayResult& result,
                       const ViewerRecording& recording);

}  // namespace mote::replay
