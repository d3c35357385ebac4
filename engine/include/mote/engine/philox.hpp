#pragma once
/// \file
/// Philox4x32-10, the counter-based generator of Salmon et al., "Parallel random numbers: as easy
/// as 1, 2, 3" (SC 2011). A draw is a pure function of (key, counter), so particle i's random
/// numbers do not depend on which thread computes it or in what order (design.md section 3).
/// Everything here is branch-free integer code that vectorizes across particles.

#include <array>
#include <cstdint>

#include "mote/engine/fast_math.hpp"

namespace mote {

/// 128-bit Philox counter as four 32-bit words.
using PhiloxCounter = std::array<std::uint32_t, 4>;
/// 64-bit Philox key as two 32-bit words.
using PhiloxKey = std::array<std::uint32_t, 2>;

namespace detail {
inline constexpr std::uint32_t kPhiloxM0 = 0xD2511F53U;  // multipliers (Salmon et al., table 2)
inline constexpr std::uint32_t kPhiloxM1 = 0xCD9E8D57U;
inline constexpr std::uint32_t kPhiloxW0 = 0x9E3779B9U;  // Weyl key increments (golden ratio,
inline constexpr std::uint32_t kPhiloxW1 = 0xBB67AE85U;  // sqrt(3) - 1)

constexpr void philox_round(PhiloxCounter& c, const PhiloxKey& k) noexcept {
  const std::uint64_t p0 = static_cast<std::uint64_t>(kPhiloxM0) * c[0];
  const std::uint64_t p1 = static_cast<std::uint64_t>(kPhiloxM1) * c[2];
  c = {static_cast<std::uint32_t>(p1 >> 32) ^ c[1] ^ k[0], static_cast<std::uint32_t>(p1),
       static_cast<std::uint32_t>(p0 >> 32) ^ c[3] ^ k[1], static_cast<std::uint32_t>(p0)};
}
}  // namespace detail

/// Philox4x32 with 10 rounds: the bijection of ctr under key (Random123's philox4x32_10).
[[nodiscard]] constexpr PhiloxCounter philox4x32_10(PhiloxCounter ctr, PhiloxKey key) noexcept {
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      key[0] += detail::kPhiloxW0;
      key[1] += detail::kPhiloxW1;
    }
    detail::philox_round(ctr, key);
  }
  return ctr;
}

/// What a random number is for; part of the counter, so purposes never share a stream.
enum class RngPurpose : std::uint32_t {
  kMotion = 1,       ///< motion-model noise
  kResample = 2,     ///< the resampling uniforms
  kInjection = 3,    ///< whether recovery replaces a particle
  kFreePose = 4,     ///< a uniform pose in free space
  kInitial = 5,      ///< initialization noise
  kRelocalize = 6,   ///< the free-space poses of a re-localization
  kLocalSearch = 7,  ///< the poses of a local search around the belief
  kUser = 64,        ///< first value free for user code
};

/// Converts 32 random bits to a float uniform in the open interval (0, 1): 23 bits, centred in
/// their bucket (k + 1/2) / 2^23, exact in float, so the value is never 0 (safe for log) and
/// never 1 (24 bits would round the top bucket up to 1).
[[nodiscard]] constexpr float bits_to_unit(std::uint32_t bits) noexcept {
  return (static_cast<float>(bits >> 9) + 0.5F) * 0x1.0p-23F;
}

/// Two independent standard normal draws from two uniforms in (0, 1) (Box-Muller).
struct NormalPair {
  float a;
  float b;
};
[[nodiscard]] inline NormalPair box_muller(float u1, float u2) noexcept {
  const float radius = fast_sqrt(-2.0F * fast_log(u1));
  const SinCos sc = sin_cos_turns(u2);
  return {radius * sc.cos, radius * sc.sin};
}

/// The random stream of one (seed, update step, purpose): block(i, j) is the j-th block of four
/// 32-bit words for particle i. Key = seed; counter = (i, j, step low, purpose | step high).
struct RngStream {
  std::uint64_t seed = 0;
  std::uint64_t step = 0;
  RngPurpose purpose = RngPurpose::kMotion;

  /// Four random 32-bit words for particle index, sub-block j.
  [[nodiscard]] PhiloxCounter block(std::uint32_t index, std::uint32_t j = 0) const noexcept {
    const PhiloxCounter ctr = {
        index, j, static_cast<std::uint32_t>(step),
        (static_cast<std::uint32_t>(purpose) << 24) ^ static_cast<std::uint32_t>(step >> 32)};
    return philox4x32_10(
        ctr, {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)});
  }

  /// Four uniforms in (0, 1) for particle index, sub-block j.
  [[nodiscard]] std::array<float, 4> uniform4(std::uint32_t index,
                                              std::uint32_t j = 0) const noexcept {
    const PhiloxCounter b = block(index, j);
    return {bits_to_unit(b[0]), bits_to_unit(b[1]), bits_to_unit(b[2]), bits_to_unit(b[3])};
  }

  /// Four standard normal draws for particle index, sub-block j (two Box-Muller pairs).
  [[nodiscard]] std::array<float, 4> normal4(std::uint32_t index,
                                             std::uint32_t j = 0) const noexcept {
    const std::array<float, 4> u = uniform4(index, j);
    const NormalPair p = box_muller(u[0], u[1]);
    const NormalPair q = box_muller(u[2], u[3]);
    return {p.a, p.b, q.a, q.b};
  }

  /// A double uniform in [0, 1) with 53 random bits, for scalar decisions (resampling offset).
  [[nodiscard]] double uniform_double(std::uint32_t index, std::uint32_t j = 0) const noexcept {
    const PhiloxCounter b = block(index, j);
    const std::uint64_t bits = (static_cast<std::uint64_t>(b[0]) << 21) ^ (b[1] >> 11);
    return static_cast<double>(bits) * 0x1.0p-53;
  }
};

}  // namespace mote
