#include "embree_packets.hpp"

namespace mote::detail {

namespace {
constexpr unsigned kAllMask = 0xFFFFFFFFU;

/// Rays lie in the plane z = 0, half way up the walls (which span z in [-1, 1]).
void fill_ray(RTCRay& r, const GridRay& ray, float max_range) noexcept {
  r.org_x = static_cast<float>(ray.ox);
  r.org_y = static_cast<float>(ray.oy);
  r.org_z = 0.0F;
  r.tnear = 0.0F;
  r.dir_x = static_cast<float>(ray.dx);
  r.dir_y = static_cast<float>(ray.dy);
  r.dir_z = 0.0F;
  r.time = 0.0F;
  r.tfar = max_range;
  r.mask = kAllMask;
  r.id = 0;
  r.flags = 0;
}
}  // namespace

Packet16::Packet16(RTCScene scene, float max_range, std::span<float> ranges) noexcept
    : scene_(scene), max_range_(max_range), ranges_(ranges) {}

void Packet16::add(const GridRay& ray, std::size_t index) noexcept {
  const int k = count_;
  RTCRay16& r = query_.ray;
  r.org_x[k] = static_cast<float>(ray.ox);
  r.org_y[k] = static_cast<float>(ray.oy);
  r.org_z[k] = 0.0F;
  r.tnear[k] = 0.0F;
  r.dir_x[k] = static_cast<float>(ray.dx);
  r.dir_y[k] = static_cast<float>(ray.dy);
  r.dir_z[k] = 0.0F;
  r.time[k] = 0.0F;
  r.tfar[k] = max_range_;
  r.mask[k] = kAllMask;
  r.id[k] = static_cast<unsigned>(k);
  r.flags[k] = 0;
  query_.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
  query_.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  index_[k] = index;
  if (++count_ == 16) flush();
}

void Packet16::flush() {
  if (count_ == 0) return;
  for (int k = 0; k < 16; ++k) valid_[k] = k < count_ ? -1 : 0;
  // Lanes past count_ hold whatever the previous packet left, or nothing at all. Embree's
  // AVX2 build splits a 16-ray packet into 8-wide halves and asserts ray.valid() (finite
  // origin, tnear >= 0) on lanes the mask excludes as well, so they get a copy of lane 0.
  RTCRay16& r = query_.ray;
  for (int k = count_; k < 16; ++k) {
    r.org_x[k] = r.org_x[0];
    r.org_y[k] = r.org_y[0];
    r.org_z[k] = 0.0F;
    r.tnear[k] = 0.0F;
    r.dir_x[k] = r.dir_x[0];
    r.dir_y[k] = r.dir_y[0];
    r.dir_z[k] = 0.0F;
    r.time[k] = 0.0F;
    r.tfar[k] = 0.0F;
    r.mask[k] = 0;
    r.id[k] = static_cast<unsigned>(k);
    r.flags[k] = 0;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect16(valid_, scene_, &context, &query_);
  for (int k = 0; k < count_; ++k) {
    ranges_[index_[k]] = hit_range(query_.hit.geomID[k], query_.ray.tfar[k], max_range_);
  }
  count_ = 0;
}

void Single1::add(const GridRay& ray, std::size_t index) {
  RTCRayHit query;
  fill_ray(query.ray, ray, max_range_);
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene_, &context, &query);
  ranges_[index] = hit_range(query.hit.geomID, query.ray.tfar, max_range_);
}

}  // namespace mote::detail
