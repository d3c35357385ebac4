#pragma once
/// \file
/// Float elementary functions written as plain polynomials so that loops calling them vectorize
/// and give the same bits in the vector body and in scalar code (design.md section 4: GCC fuses
/// std::sin/std::cos of one argument into sincosf, which has no vector form; libm's vector
/// variants need -ffast-math). Accuracy: a few ulp of float over the ranges stated.

#include <bit>
#include <cstdint>

namespace mote {

/// sin and cos of one angle.
struct SinCos {
  float sin;
  float cos;
};

namespace detail {
// Taylor polynomials on [-pi/4, pi/4]: truncation error below (pi/4)^9 / 9! = 3e-7.
[[nodiscard]] inline float sin_poly(float r) noexcept {
  const float r2 = r * r;
  return r * (1.0F + r2 * (-1.0F / 6 + r2 * (1.0F / 120 + r2 * (-1.0F / 5040 + r2 / 362880))));
}
[[nodiscard]] inline float cos_poly(float r) noexcept {
  const float r2 = r * r;
  return 1.0F +
         r2 * (-0.5F + r2 * (1.0F / 24 + r2 * (-1.0F / 720 + r2 * (1.0F / 40320 - r2 / 3628800))));
}
// Quadrant selection: (sin, cos) of r + q * pi / 2.
[[nodiscard]] inline SinCos rotate_quadrant(float s, float c, std::int32_t q) noexcept {
  const std::int32_t k = q & 3;
  const float sin_out = (k == 0) ? s : (k == 1) ? c : (k == 2) ? -s : -c;
  const float cos_out = (k == 0) ? c : (k == 1) ? -s : (k == 2) ? -c : s;
  return {sin_out, cos_out};
}
}  // namespace detail

namespace detail {
// v if |v| < 1e9, else 0 (NaN included): keeps a float inside int32's range before it is
// converted (converting NaN or |v| >= 2^31 is undefined). A compare and a blend: loops still
// vectorize.
// Bit masks rather than ?: on floats, which GCC 12 leaves as control flow here (the loops
// calling these would stay scalar).
[[nodiscard]] inline std::uint32_t int32_range_mask(float v) noexcept {
  return ((v > -1e9F) & (v < 1e9F)) ? ~0U : 0U;
}
[[nodiscard]] inline float int32_safe(float v) noexcept {
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(v) & int32_range_mask(v));
}
}  // namespace detail

/// sin and cos of a in radians, |a| < 1e5 (Cody-Waite reduction by pi/2 in two parts). NaN,
/// +-inf and |a| >= 1.5e9 give NaN; between 1e5 and 1.5e9 the values are inaccurate.
[[nodiscard]] inline SinCos fast_sin_cos(float a) noexcept {
  constexpr float kTwoOverPi = 0.636619772F;
  constexpr float kPiOver2Hi = 1.5703125F;         // exact in 8 bits
  constexpr float kPiOver2Lo = 4.83826794897e-4F;  // pi/2 - kPiOver2Hi
  const std::uint32_t in_range = detail::int32_range_mask(a * kTwoOverPi);
  const float shifted =
      std::bit_cast<float>(std::bit_cast<std::uint32_t>(a * kTwoOverPi) & in_range);
  const auto q = static_cast<std::int32_t>(shifted + (shifted >= 0.0F ? 0.5F : -0.5F));
  const float qf = static_cast<float>(q);
  // The 0 taken for an unusable angle would give the polynomials a huge r: a quiet NaN's bits
  // are OR-ed in instead.
  const float reduced = (a - qf * kPiOver2Hi) - qf * kPiOver2Lo;
  const float r =
      std::bit_cast<float>(std::bit_cast<std::uint32_t>(reduced) | (~in_range & 0x7fc00000U));
  return detail::rotate_quadrant(detail::sin_poly(r), detail::cos_poly(r), q);
}

/// sin and cos of 2 pi t for t in [0, 1) (Box-Muller's angle); exact quadrant split of t.
[[nodiscard]] inline SinCos sin_cos_turns(float t) noexcept {
  constexpr float kTwoPi = 6.28318530718F;
  const float scaled = t * 4.0F;
  const auto q = static_cast<std::int32_t>(scaled + 0.5F);
  const float r = (scaled - static_cast<float>(q)) * (kTwoPi / 4.0F);
  return detail::rotate_quadrant(detail::sin_poly(r), detail::cos_poly(r), q);
}

/// Natural log of x > 0 (finite, normal); atanh series on the mantissa in [sqrt(1/2), sqrt(2)).
[[nodiscard]] inline float fast_log(float x) noexcept {
  constexpr float kLn2 = 0.693147181F;
  const auto bits = std::bit_cast<std::uint32_t>(x);
  // Re-bias so the mantissa m lands in [sqrt(1/2), sqrt(2)): 0x3f3504f3 is sqrt(1/2).
  const std::uint32_t shifted = bits - 0x3f3504f3U;
  const auto exponent = static_cast<std::int32_t>(shifted) >> 23;
  const float m = std::bit_cast<float>((shifted & 0x007fffffU) + 0x3f3504f3U);
  const float s = (m - 1.0F) / (m + 1.0F);  // |s| <= 0.172, series error < 2e-9
  const float s2 = s * s;
  const float series = 2.0F * s * (1.0F + s2 * (1.0F / 3 + s2 * (0.2F + s2 * (1.0F / 7 + s2 / 9))));
  return static_cast<float>(exponent) * kLn2 + series;
}

/// exp(x) for x <= 0 (larger x is taken as 0); exactly 0 below -87, for -inf and for NaN (a
/// NaN log-weight weighs nothing). Branch-free: the result is masked rather than selected, so
/// GCC vectorizes callers even with trapping math.
[[nodiscard]] inline float fast_exp(float x) noexcept {
  constexpr float kLog2e = 1.44269504F;
  constexpr float kLn2Hi = 0.693145752F;  // Cody-Waite split of ln 2
  constexpr float kLn2Lo = 1.42860677e-6F;
  // Written so that NaN fails the first test and never reaches the int conversion.
  const float clamped = x >= -87.0F ? (x > 0.0F ? 0.0F : x) : -87.0F;
  const float kf = static_cast<float>(static_cast<std::int32_t>(clamped * kLog2e - 0.5F));
  const float r = (clamped - kf * kLn2Hi) - kf * kLn2Lo;  // |r| <= ln2 / 2
  // Taylor to degree 7 on |r| <= 0.35: error below 0.35^8 / 8! = 6e-9 relative.
  const float p =
      1.0F +
      r * (1.0F +
           r * (0.5F +
                r * (1.0F / 6 + r * (1.0F / 24 + r * (1.0F / 120 + r * (1.0F / 720 + r / 5040))))));
  const auto scale =
      std::bit_cast<float>(static_cast<std::uint32_t>((static_cast<std::int32_t>(kf) + 127) << 23));
  const std::uint32_t keep = x >= -87.0F ? ~0U : 0U;
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(p * scale) & keep);
}

/// Square root through the hardware instruction (correctly rounded, vectorizes without errno).
[[nodiscard]] inline float fast_sqrt(float x) noexcept { return __builtin_sqrtf(x); }

}  // namespace mote

namespace mote {

/// Wraps a float angle in radians (|a| < 1e5) to (-pi, pi] without a libm call. NaN stays NaN,
/// +-inf stays infinite; beyond 1e5 the result is unspecified, but defined.
[[nodiscard]] inline float fast_wrap_angle(float a) noexcept {
  constexpr float kTwoPi = 6.28318530718F;
  constexpr float kPi = 3.14159265359F;
  const float turns = detail::int32_safe(a * (1.0F / kTwoPi));
  const auto k = static_cast<std::int32_t>(turns + (turns >= 0.0F ? 0.5F : -0.5F));
  const float r = a - static_cast<float>(k) * kTwoPi;
  return r <= -kPi ? r + kTwoPi : (r > kPi ? r - kTwoPi : r);
}

}  // namespace mote
