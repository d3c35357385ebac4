#pragma once
/// \file
/// Internal: what both casters share so that they trace exactly the same rays. Rays live in the
/// grid frame (OccupancyGrid::to_grid_frame: origin at the lower-left corner of cell (0, 0), axes
/// along the grid), so an origin yaw costs one transform per particle and the walls stay axis
/// aligned.

#include <cmath>
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

/// A ray in the grid frame: origin (m) and unit direction. Casters round it to float (what
/// Embree traces) before use, so both trace exactly the same ray.
struct GridRay {
  double ox = 0.0;
  double oy = 0.0;
  double dx = 1.0;
  double dy = 0.0;
};

/// Origins closer than this to a grid line (m) are moved onto it. Far below any laser's
/// resolution, and above float rounding of map coordinates up to 128 m (ulp 7.6e-6 m): a ray
/// built on a cell edge then lies exactly on Embree's wall plane instead of an ulp to either
/// side, where Embree's edge tolerance and the grid walk could decide differently.
inline constexpr double kSnapDistance = 2e-5;
/// Direction components smaller than this are zero: cos(pi / 2) is 6e-17, not 0.
inline constexpr double kAxisSnap = 1e-12;

/// A direction component as traced: tiny components zeroed, rounded to float.
[[nodiscard]] inline double snap_direction(double d) noexcept {
  return std::abs(d) < kAxisSnap ? 0.0 : static_cast<double>(static_cast<float>(d));
}

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
  /// v (m) moved onto the nearest grid line when within kSnapDistance of it, rounded to float.
  [[nodiscard]] double snap_to_line(double v, int count) const noexcept;
  /// The ray both casters trace: origin snapped to grid lines, direction components below
  /// kAxisSnap set to zero, everything rounded to float (what Embree traces).
  [[nodiscard]] GridRay prepare(const GridRay& r) const noexcept;
  /// The start rule: a sensor at grid frame point (m) reads 0 when it lies in a blocking cell or
  /// on the boundary of one (exactly on a grid line after snapping: Embree would report the face
  /// it sits on, or the far side of the wall). Off-map points never block.
  [[nodiscard]] bool blocks_start(double gx, double gy) const noexcept;
};

/// The sensor of one particle in the grid frame: position (m, snapped and rounded as in
/// CellMask::prepare) and heading as cos/sin.
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
  BatchRays(const GridFrame& frame, const CellMask& mask, const RayBatch& batch,
            std::size_t ranges_size);

  [[nodiscard]] SensorFrame sensor(std::size_t particle) const noexcept;
  [[nodiscard]] GridRay ray(const SensorFrame& sensor, std::size_t beam) const noexcept {
    const double cb = beam_cos_[beam];
    const double sb = beam_sin_[beam];
    return {sensor.ox, sensor.oy, snap_direction(sensor.c * cb - sensor.s * sb),
            snap_direction(sensor.s * cb + sensor.c * sb)};
  }
  /// Beam b's direction in the sensor frame, as ray() rotates it.
  [[nodiscard]] double beam_cos(std::size_t beam) const noexcept { return beam_cos_[beam]; }
  [[nodiscard]] double beam_sin(std::size_t beam) const noexcept { return beam_sin_[beam]; }
  [[nodiscard]] std::size_t beams() const noexcept { return beam_cos_.size(); }
  [[nodiscard]] std::size_t particles() const noexcept { return batch_.particle_count(); }
  [[nodiscard]] float max_range() const noexcept { return batch_.max_range; }

 private:
  const GridFrame& frame_;
  const CellMask& mask_;
  const RayBatch& batch_;
  std::vector<double> beam_cos_;
  std::vector<double> beam_sin_;
};

/// Throws ConfigError unless max_range is a positive finite number of metres.
void check_max_range(float max_range);

}  // namespace mote::detail
