#pragma once
/// \file
/// Internal: collects rays into Embree queries and writes the ranges back. Rays are added in
/// particle index order, so which rays share a packet depends only on the chunk (a multiple of
/// the grain), never on the thread that runs it (design.md section 3, "Determinism").

#include <cstddef>
#include <span>

#include "embree_device.hpp"
#include "ray_setup.hpp"

namespace mote::detail {

/// Range of one lane after a query: the hit distance, or max_range when nothing was hit.
[[nodiscard]] inline float hit_range(unsigned geom_id, float tfar, float max_range) noexcept {
  return geom_id == RTC_INVALID_GEOMETRY_ID ? max_range : (tfar < max_range ? tfar : max_range);
}

/// 16-wide packets cast with rtcIntersect16.
class Packet16 {
 public:
  Packet16(RTCScene scene, float max_range, std::span<float> ranges) noexcept;
  /// Queues the ray whose range goes to ranges[index]; casts when 16 are queued.
  void add(const GridRay& ray, std::size_t index) noexcept;
  /// Casts whatever is queued (the remaining lanes are masked off).
  void flush();

 private:
  RTCRayHit16 query_;
  alignas(64) int valid_[16];
  std::size_t index_[16];
  int count_ = 0;
  RTCScene scene_;
  float max_range_;
  std::span<float> ranges_;
};

/// One ray at a time with rtcIntersect1: the unpacketized baseline.
class Single1 {
 public:
  Single1(RTCScene scene, float max_range, std::span<float> ranges) noexcept
      : scene_(scene), max_range_(max_range), ranges_(ranges) {}
  void add(const GridRay& ray, std::size_t index);
  void flush() noexcept {}

 private:
  RTCScene scene_;
  float max_range_;
  std::span<float> ranges_;
};

}  // namespace mote::detail
