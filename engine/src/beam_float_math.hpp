#pragma once
// Float exp, expm1, log and erfc for the batched beam model (engine-internal): plain polynomials
// without a division or a branch, so that loops over particles calling them vectorize. Unlike
// fast_math.hpp's fast_exp and fast_log, whose r / 5040 and (m - 1) / (m + 1) compile to vector
// divisions (the slowest vector instruction), every coefficient here is multiplied.

#include <bit>
#include <cstdint>

namespace mote::detail {

// c ? a : b through bit masks. GCC 12 does not if-convert a ?: whose arm holds a float-to-int
// conversion (it will not speculate it), which would keep the whole loop scalar.
[[nodiscard]] inline float select(bool c, float a, float b) noexcept {
  const std::uint32_t mask = c ? ~0U : 0U;
  return std::bit_cast<float>((std::bit_cast<std::uint32_t>(a) & mask) |
                              (std::bit_cast<std::uint32_t>(b) & ~mask));
}

// x = k ln 2 + r with |r| <= ln 2 / 2 and scale = 2^k, for x in [-87, 0] (Cody-Waite: kf * kLn2Hi
// is exact, kLn2Hi having 16 significant bits).
struct ExpReduction {
  float r;
  float scale;
};

[[nodiscard]] inline ExpReduction reduce_exp(float x) noexcept {
  constexpr float kLog2e = 1.44269504F;
  constexpr float kLn2Hi = 0.693145752F;
  constexpr float kLn2Lo = 1.42860677e-6F;
  const float kf = static_cast<float>(static_cast<std::int32_t>(x * kLog2e - 0.5F));
  const float r = (x - kf * kLn2Hi) - kf * kLn2Lo;
  const auto scale =
      std::bit_cast<float>(static_cast<std::uint32_t>((static_cast<std::int32_t>(kf) + 127) << 23));
  return {r, scale};
}

// (e^r - 1) / r by Taylor's series to r^6 / 7!: for |r| <= 0.35 the truncation is below
// 0.35^7 / 8! = 2e-8 relative.
[[nodiscard]] inline float expm1_ratio(float r) noexcept {
  return 1.0F + r * (1.0F / 2 +
                     r * (1.0F / 6 + r * (1.0F / 24 + r * (1.0F / 120 +
                                                           r * (1.0F / 720 + r * (1.0F / 5040))))));
}

// exp(x) for x <= 0; exactly 0 below -87 and for NaN (which fails x >= -87, so never reaches
// reduce_exp's int conversion). A few float ulp.
[[nodiscard]] inline float exp_nonpositive(float x) noexcept {
  const float clamped = x >= -87.0F ? (x > 0.0F ? 0.0F : x) : -87.0F;
  const ExpReduction e = reduce_exp(clamped);
  const float value = e.scale + e.scale * (e.r * expm1_ratio(e.r));
  const std::uint32_t keep = x >= -87.0F ? ~0U : 0U;
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(value) & keep);
}

// exp(x) - 1 for x <= 0 without cancellation near 0: e^x - 1 = 2^k (e^r - 1) + (2^k - 1), where
// k = 0 (no subtraction at all) for |x| < 0.35 and the subtraction loses at most a factor 1.7
// beyond. NaN is taken as -87 (result -1), never converted.
[[nodiscard]] inline float expm1_nonpositive(float x) noexcept {
  const float clamped = x >= -87.0F ? (x > 0.0F ? 0.0F : x) : -87.0F;
  const ExpReduction e = reduce_exp(clamped);
  return e.scale * (e.r * expm1_ratio(e.r)) + (e.scale - 1.0F);
}

// erfc(x) for x >= 0 given t = 1 / (1 + x / 2): Press et al., Numerical Recipes in C (2nd ed.),
// section 6.2, erfcc, a Chebyshev fit with fractional error below 1.2e-7 for every x >= 0;
// exactly 0 past x = 9.3.
[[nodiscard]] inline float erfc_given_t(float x, float t) noexcept {
  const float poly =
      -1.26551223F +
      t * (1.00002368F +
           t * (0.37409196F +
                t * (0.09678418F +
                     t * (-0.18628806F +
                          t * (0.27886807F +
                               t * (-1.13520398F +
                                    t * (1.48851587F + t * (-0.82215223F + t * 0.17087277F))))))));
  return t * exp_nonpositive(poly - x * x);
}

[[nodiscard]] inline float erfc_nonneg(float x) noexcept {
  return erfc_given_t(x, 1.0F / (1.0F + 0.5F * x));
}

// erfc(a) + erfc(b) for a, b >= 0 with the two reciprocals from one division (2 more roundings).
[[nodiscard]] inline float erfc_sum(float a, float b) noexcept {
  const float one_plus_a = 1.0F + 0.5F * a;
  const float one_plus_b = 1.0F + 0.5F * b;
  const float inv = 1.0F / (one_plus_a * one_plus_b);
  return erfc_given_t(a, one_plus_b * inv) + erfc_given_t(b, one_plus_a * inv);
}

// Natural log of a finite normal x > 0: the mantissa m in [sqrt(1/2), sqrt(2)) as fast_log takes
// it, then Cephes' logf polynomial in m - 1 (S. Moshier, Cephes single/logf.c; Eigen's plog uses
// the same): peak relative error 7.6e-8.
[[nodiscard]] inline float log_normal(float x) noexcept {
  const std::uint32_t shifted = std::bit_cast<std::uint32_t>(x) - 0x3f3504f3U;  // sqrt(1/2)
  const auto e = static_cast<float>(static_cast<std::int32_t>(shifted) >> 23);
  const float m = std::bit_cast<float>((shifted & 0x007fffffU) + 0x3f3504f3U) - 1.0F;
  const float m2 = m * m;
  float p = 7.0376836292E-2F;
  p = p * m - 1.1514610310E-1F;
  p = p * m + 1.1676998740E-1F;
  p = p * m - 1.2420140846E-1F;
  p = p * m + 1.4249322787E-1F;
  p = p * m - 1.6668057665E-1F;
  p = p * m + 2.0000714765E-1F;
  p = p * m - 2.4999993993E-1F;
  p = p * m + 3.3333331174E-1F;
  // ln 2 = 0.693359375 - 2.12194440e-4, the first part exact in 10 bits (Cody-Waite).
  const float tail = p * m * m2 - 2.12194440e-4F * e - 0.5F * m2;
  return (m + tail) + 0.693359375F * e;
}

}  // namespace mote::detail
