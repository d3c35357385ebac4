#include "mote/engine/philox.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "engine_test_util.hpp"
#include "mote/engine/fast_math.hpp"

namespace mote {
namespace {

// Random123 kat_vectors, philox4x32_10 lines.
TEST(Philox, MatchesKnownAnswerVectors) {
  EXPECT_EQ(philox4x32_10({0, 0, 0, 0}, {0, 0}),
            (PhiloxCounter{0x6627e8d5U, 0xe169c58dU, 0xbc57ac4cU, 0x9b00dbd8U}));
  EXPECT_EQ(philox4x32_10({0xffffffffU, 0xffffffffU, 0xffffffffU, 0xffffffffU},
                          {0xffffffffU, 0xffffffffU}),
            (PhiloxCounter{0x408f276dU, 0x41c83b0eU, 0xa20bc7c6U, 0x6d5451fdU}));
  EXPECT_EQ(philox4x32_10({0x243f6a88U, 0x85a308d3U, 0x13198a2eU, 0x03707344U},
                          {0xa4093822U, 0x299f31d0U}),
            (PhiloxCounter{0xd16cfe09U, 0x94fdccebU, 0x5001e420U, 0x24126ea1U}));
}

TEST(Philox, IsAConstantExpression) {
  static_assert(philox4x32_10({0, 0, 0, 0}, {0, 0})[0] == 0x6627e8d5U);
}

TEST(Philox, StreamsDifferBySeedStepPurposeAndIndex) {
  const RngStream base{7, 3, RngPurpose::kMotion};
  const PhiloxCounter b = base.block(5);
  EXPECT_NE(b, (RngStream{8, 3, RngPurpose::kMotion}.block(5)));
  EXPECT_NE(b, (RngStream{7, 4, RngPurpose::kMotion}.block(5)));
  EXPECT_NE(b, (RngStream{7, 3, RngPurpose::kResample}.block(5)));
  EXPECT_NE(b, base.block(6));
  EXPECT_NE(b, base.block(5, 1));
  EXPECT_EQ(b, base.block(5));
}

TEST(Philox, UnitFloatsStayInsideTheOpenInterval) {
  EXPECT_GT(bits_to_unit(0), 0.0F);
  EXPECT_LT(bits_to_unit(0xffffffffU), 1.0F);
}

TEST(Philox, UniformDrawsHaveUniformMoments) {
  const RngStream rng{42, 1, RngPurpose::kUser};
  constexpr std::size_t kN = 100000;
  const test::SampleStats s = test::sample_stats(kN * 4, [&](std::size_t i) {
    return static_cast<double>(rng.uniform4(static_cast<std::uint32_t>(i / 4))[i % 4]);
  });
  EXPECT_NEAR(s.mean, 0.5, s.mean_tolerance());
  // Variance of a uniform's sample variance: (1/80 - 1/144) / n; 5 standard errors.
  EXPECT_NEAR(s.variance, 1.0 / 12, 5.0 * std::sqrt((1.0 / 80 - 1.0 / 144) / (4.0 * kN)));
}

TEST(Philox, NormalDrawsHaveStandardNormalMoments) {
  const RngStream rng{42, 2, RngPurpose::kUser};
  constexpr std::size_t kN = 100000;
  const test::SampleStats s = test::sample_stats(kN * 4, [&](std::size_t i) {
    return static_cast<double>(rng.normal4(static_cast<std::uint32_t>(i / 4))[i % 4]);
  });
  EXPECT_NEAR(s.mean, 0.0, s.mean_tolerance());
  EXPECT_NEAR(s.variance, 1.0, s.variance_tolerance(1.0));
  // Tail mass beyond 3 sigma: 0.0027 of draws, binomial standard error.
  std::size_t tail = 0;
  for (std::uint32_t i = 0; i < kN; ++i) {
    for (const float z : rng.normal4(i)) tail += std::abs(z) > 3.0F ? 1 : 0;
  }
  const double p = 0.0026998;
  EXPECT_NEAR(static_cast<double>(tail) / (4.0 * kN), p, 5.0 * std::sqrt(p * (1 - p) / (4.0 * kN)));
}

TEST(FastMath, SinCosMatchLibmToFloatAccuracy) {
  for (double a = -60.0; a <= 60.0; a += 0.00731) {
    const SinCos sc = fast_sin_cos(static_cast<float>(a));
    const double af = static_cast<float>(a);
    EXPECT_NEAR(sc.sin, std::sin(af), 2e-6) << a;
    EXPECT_NEAR(sc.cos, std::cos(af), 2e-6) << a;
  }
  for (float t = 0.0F; t < 1.0F; t += 0.001F) {
    const SinCos sc = sin_cos_turns(t);
    EXPECT_NEAR(sc.sin, std::sin(2 * std::numbers::pi * t), 1e-6);
    EXPECT_NEAR(sc.cos, std::cos(2 * std::numbers::pi * t), 1e-6);
  }
}

TEST(FastMath, LogAndExpMatchLibm) {
  for (double x = 1e-30; x < 1e30; x *= 1.37) {
    EXPECT_NEAR(fast_log(static_cast<float>(x)), std::log(static_cast<float>(x)),
                2e-6 * std::max(1.0, std::abs(std::log(x))));
  }
  for (double x = -86.0; x <= 0.0; x += 0.0173) {
    const double e = std::exp(static_cast<double>(static_cast<float>(x)));
    EXPECT_NEAR(fast_exp(static_cast<float>(x)), e, 4e-7 * e) << x;
  }
  EXPECT_EQ(fast_exp(-100.0F), 0.0F);
  EXPECT_EQ(fast_exp(-INFINITY), 0.0F);
}

TEST(FastMath, WrapsAnglesIntoTheHalfOpenInterval) {
  EXPECT_FLOAT_EQ(fast_wrap_angle(3.0F * std::numbers::pi_v<float>), std::numbers::pi_v<float>);
  EXPECT_NEAR(fast_wrap_angle(-0.5F - 4.0F * std::numbers::pi_v<float>), -0.5F, 1e-6);
  EXPECT_GT(fast_wrap_angle(-std::numbers::pi_v<float>), 0.0F);
}

TEST(FastMath, NonFiniteArgumentsGiveDefinedResults) {
  // Each helper converts a float to int32; a NaN or huge argument must not reach that
  // conversion (undefined behaviour, caught by -fsanitize=float-cast-overflow).
  const float kNaN = std::numeric_limits<float>::quiet_NaN();
  const float kInf = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(std::isnan(fast_wrap_angle(kNaN)));
  EXPECT_EQ(fast_exp(kNaN), 0.0F);  // NaN weighs nothing, as -inf
  EXPECT_EQ(fast_exp(-kInf), 0.0F);
  EXPECT_EQ(fast_exp(kInf), 1.0F);  // clamped to x <= 0
  EXPECT_TRUE(std::isnan(fast_sin_cos(kNaN).sin));
  EXPECT_TRUE(std::isnan(fast_sin_cos(kNaN).cos));
  for (const float a : {kInf, -kInf, 3e38F, -3e38F}) {
    (void)fast_wrap_angle(a);  // outside |a| < 1e5 the value is unspecified, but defined
    const SinCos sc = fast_sin_cos(a);
    EXPECT_TRUE(std::isnan(sc.sin) || std::abs(sc.sin) <= 1.0F) << a;
  }
}

}  // namespace
}  // namespace mote
