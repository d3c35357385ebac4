#pragma once
/// \file
/// Internal: what both casters share so that they trace exactly the same rays. Rays live in the
/// grid frame (OccupancyGrid::to_grid_frame: origin at the lower-left corner of cell (0, 0), axes
/// along the grid), so an origin yaw costs one transform per particle and the walls stay axis
/// aligned.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "mote/maps/occupancy_grid.hpp"
#include "mote/raycast/ray_batch.hpp"

namespace mote::detail {

/// One cell per byte, 1 where rays stop: occupied cells and, if unknown_blocks, unknown ones.
[[nodiscard]] std::vector<std::uint8_t> blocking_mask(const OccupancyGrid& grid,
                                                      bool unknown_blocks);

/// Read-only view of a blocking mask with the grid's geometry. Grid line k sits at line(k), the
/// float product Embree's wall vertices use, and cell k is the half-open [line(k), line(k + 1)):
/// both casters locate points with these, so they agree on which side of a wall a ray starts.
struct CellMask {
  int width = 0;
  int height = 0;
  float resolution = 1.0F;  ///< m per cell
  const std::uint8_t* cells = nullptr;

  [[nodiscard]] bool blocks(int i, int j) const noexcept {
    return cells[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(i)] != 0;
  }
  /// Blocking state with off-map cells free.
  [[nodiscard]] bool blocks_or_free(int i, int j) const noexcept {
    return i >= 0 && j >= 0 && i < width && j < height && blocks(i, j);
  }
  /// Coordinate (m) of grid line k.
  [[nodiscard]] double line(int k) const noexcept {
    return static_cast<double>(static_cast<float>(k) * resolution);
  }
  /// The cell k with line(k) <= v < line(k + 1), clamped to [-1, count].
  [[nodiscard]] int cell_of(double v, int count) const noexcept;
  /// Whether a grid frame point (m) lies in a blocking cell; off-map points never do.
  [[nodiscard]] bool blocks_point(double gx, double gy) const noexcept;
};

/// A ray in the grid frame: origin (m) and unit direction. Casters round it to float (what
/// Embree traces) before use, so both trace exactly the same ray.
struct GridRay {
  double ox = 0.0;
  double oy = 0.0;
  double dx = 1.0;
  double dy = 0.0;
};

/// The ray rounded through float, as Embree traces it.
[[nodiscard]] inline GridRay to_float(const GridRay& r) noexcept {
  return {static_cast<float>(r.ox), static_cast<float>(r.oy), static_cast<float>(r.dx),
          static_cast<float>(r.dy)};
}

/// The sensor of one particle in the grid frame: position (m) and heading as cos/sin.
struct SensorFrame {
  double ox = 0.0;
  double oy = 0.0;
  double c = 1.0;
  double s = 0.0;
  bool finite = true;
};

/// Map frame to grid frame for a grid whose lower-left corner sits at `origin`.
class GridFrame {
 public:
  explicit GridFrame(const Pose2& origin) noexcept;
  /// The same arithmetic as OccupancyGrid::to_grid_frame.
  [[nodiscard]] Point2 to_grid(double x, double y) const noexcept;
  /// A single ray from a map frame point at a map frame angle (rad).
  [[nodiscard]] GridRay ray(Point2 origin, double angle) const noexcept;
  [[nodiscard]] const Pose2& origin() const noexcept { return origin_; }

 private:
  Pose2 origin_;
  double c_;
  double s_;
};

/// Validated view of a RayBatch that hands out sensor frames and per-beam rays. Each beam
/// direction is the sensor heading rotated by the beam angle, with cos/sin of the beam angles
/// computed once per cast instead of once per ray.
class BatchRays {
 public:
  /// Throws ConfigError when the batch or the range array do not fit together.
  BatchRays(const GridFrame& frame, const RayBatch& batch, std::size_t ranges_size);

  [[nodiscard]] SensorFrame sensor(std::size_t particle) const noexcept;
  [[nodiscard]] GridRay ray(const SensorFrame& sensor, std::size_t beam) const noexcept {
    const double cb = beam_cos_[beam];
    const double sb = beam_sin_[beam];
    return {sensor.ox, sensor.oy, sensor.c * cb - sensor.s * sb, sensor.s * cb + sensor.c * sb};
  }
  [[nodiscard]] std::size_t beams() const noexcept { return beam_cos_.size(); }
  [[nodiscard]] std::size_t particles() const noexcept { return batch_.particle_count(); }
  [[nodiscard]] float max_range() const noexcept { return batch_.max_range; }

 private:
  const GridFrame& frame_;
  const RayBatch& batch_;
  std::vector<double> beam_cos_;
  std::vector<double> beam_sin_;
};

/// Throws ConfigError unless max_range is a positive finite number of metres.
void check_max_range(float max_range);

}  // namespace mote::detail
