#pragma once
/// \file
/// What every mote ray caster takes and gives: options, a batch of rays described as particle
/// poses times beam angles, and the concept both casters (Embree and the grid walk) satisfy, so
/// the beam sensor model can template over either.

#include <concepts>
#include <cstddef>
#include <span>

#include "mote/core/free_space.hpp"
#include "mote/core/pose.hpp"

namespace mote {

/// How a caster sees the map.
struct RayCastOptions {
  /// Unknown cells stop rays, as in ROS amcl's map_calc_range; false lets rays pass through them.
  bool unknown_blocks = true;
  /// Embree only: true casts 16-ray packets (rtcIntersect16), false one ray at a time
  /// (rtcIntersect1). Both give the same ranges; packets are faster.
  bool packets = true;
  /// Particles per parallel task; chunk boundaries depend on this only, never on the thread
  /// count, so results are identical for any number of threads (design.md section 3).
  std::size_t particle_grain = 64;
};

/// Rays cast from every particle along every beam. The ray of (particle p, beam b) starts at the
/// sensor, placed at compose(pose_p, sensor_offset), and points at beam_angles[b] in the sensor
/// frame. Results are particle-major: ranges[p * beam_count() + b].
struct RayBatch {
  std::span<const float> x;            ///< m, particle x in the map frame
  std::span<const float> y;            ///< m, particle y in the map frame
  std::span<const float> theta;        ///< rad, particle heading in the map frame
  std::span<const float> beam_angles;  ///< rad, beam directions in the sensor frame
  Pose2 sensor_offset{};               ///< sensor mounting pose in the robot frame (m, rad)
  float max_range = 0.0F;              ///< m, rays that hit nothing closer report this

  [[nodiscard]] std::size_t particle_count() const noexcept { return x.size(); }
  [[nodiscard]] std::size_t beam_count() const noexcept { return beam_angles.size(); }
  [[nodiscard]] std::size_t ray_count() const noexcept { return x.size() * beam_angles.size(); }
};

/// A ray caster over a fixed map: batched casts into a particle-major range array, and single
/// rays from a map frame point at a map frame angle (rad), both in metres clamped to max_range.
template <class C>
concept RayCasterLike = requires(const C& caster, const RayBatch& batch, std::span<float> ranges,
                                 Point2 origin, double angle, float max_range) {
  caster.cast(batch, ranges);
  { caster.cast_one(origin, angle, max_range) } -> std::convertible_to<float>;
};

}  // namespace mote
