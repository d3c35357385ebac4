#include "mote/engine/resample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "mote/engine/executor.hpp"
#include "mote/engine/philox.hpp"
#include "mote/engine/weights.hpp"

namespace mote {
namespace {

// A store whose particle i has x = i and random normalized weights (some exactly zero).
ParticleStore weighted_store(std::size_t n, std::uint64_t seed) {
  ParticleStore store(n);
  const ParticleView p = store.view();
  const RngStream rng{seed, 0, RngPurpose::kUser};
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<float, 4> u = rng.uniform4(static_cast<std::uint32_t>(i));
    p.x[i] = static_cast<float>(i);
    p.y[i] = -static_cast<float>(i);
    p.theta[i] = u[2];
    p.logw[i] = u[0] < 0.1F ? -INFINITY : 4.0F * std::log(u[1]);
  }
  EXPECT_TRUE(normalize(p).ok());
  return store;
}

std::vector<float> column(const ParticleStore& s, int which) {
  const ConstParticleView v = s.view();
  const float* c = which == 0 ? v.x : which == 1 ? v.y : which == 2 ? v.theta : v.logw;
  return {c, c + v.size()};
}

TEST(ResampleSystematic, EqualsTheSerialReferenceForAnyThreadsAndGrain) {
  for (const std::size_t n_out : {10007UL, 3000UL, 25000UL}) {
    ParticleStore reference = weighted_store(10007, 5);
    resample_systematic_serial(reference, n_out, 77, 3);
    for (const int threads : {1, 2, 4}) {
      for (const std::size_t grain : {16UL, 1000UL}) {
        ParticleStore store = weighted_store(10007, 5);
        const Executor ex(threads);
        ex([&] { resample_systematic(store, n_out, 77, 3, grain); });
        ASSERT_EQ(store.size(), n_out);
        for (int c = 0; c < 4; ++c) ASSERT_EQ(column(store, c), column(reference, c));
      }
    }
  }
}

// Every particle gets floor(n w) or ceil(n w) copies. The fixed-point weights come from float
// exponentials (relative error ~1e-7), so n w is known to 1e-7 n w: 1e-5 covers n w < 100.
TEST(ResampleSystematic, GivesEachParticleFloorOrCeilOfItsExpectedCopies) {
  for (const std::size_t n_out : {10007UL, 4321UL}) {
    ParticleStore store = weighted_store(10007, 9);
    std::vector<double> expected(store.size());
    for (std::size_t i = 0; i < store.size(); ++i) {
      expected[i] = static_cast<double>(n_out) * std::exp(double{store.view().logw[i]});
    }
    resample_systematic(store, n_out, 1, 1, 256);
    std::vector<std::size_t> copies(expected.size());
    for (const float x : column(store, 0)) ++copies[static_cast<std::size_t>(x)];
    for (std::size_t i = 0; i < copies.size(); ++i) {
      ASSERT_GE(static_cast<double>(copies[i]), std::floor(expected[i] - 1e-5)) << i;
      ASSERT_LE(static_cast<double>(copies[i]), std::ceil(expected[i] + 1e-5)) << i;
    }
    EXPECT_FLOAT_EQ(store.view().logw[0], -std::log(static_cast<float>(n_out)));
  }
}

TEST(ResampleSystematic, ReusesItsBuffersWhenTheCountShrinksAndGrows) {
  ParticleStore store = weighted_store(5000, 2);
  const std::size_t capacity = store.capacity();
  const float* buffers[2] = {store.view().x, store.spare(1).x};
  resample_systematic(store, 1000, 1, 1);
  EXPECT_EQ(store.view().x, buffers[1]);
  resample_systematic(store, 4990, 1, 2);
  EXPECT_EQ(store.view().x, buffers[0]);
  EXPECT_EQ(store.capacity(), capacity);
}

// The baselines: right count, only particles with positive weight, residual's floor copies.
TEST(ResampleBaselines, DrawOnlyWeightedParticles) {
  using Scheme = void (*)(ParticleStore&, std::size_t, std::uint64_t, std::uint64_t);
  const Scheme schemes[] = {
      [](ParticleStore& s, std::size_t n, std::uint64_t a, std::uint64_t b) {
        resample_multinomial(s, n, a, b);
      },
      [](ParticleStore& s, std::size_t n, std::uint64_t a, std::uint64_t b) {
        resample_stratified(s, n, a, b);
      },
      [](ParticleStore& s, std::size_t n, std::uint64_t a, std::uint64_t b) {
        resample_residual(s, n, a, b);
      },
  };
  for (const Scheme scheme : schemes) {
    ParticleStore store = weighted_store(2000, 4);
    const std::vector<float> logw = column(store, 3);
    scheme(store, 3000, 8, 1);
    ASSERT_EQ(store.size(), 3000U);
    std::map<std::size_t, std::size_t> copies;
    for (const float x : column(store, 0)) ++copies[static_cast<std::size_t>(x)];
    for (const auto& [i, count] : copies) ASSERT_GT(logw[i], -INFINITY) << i;
  }
  ParticleStore store = weighted_store(2000, 4);
  const std::vector<float> logw = column(store, 3);
  resample_residual(store, 3000, 8, 1);
  std::vector<std::size_t> copies(2000);
  for (const float x : column(store, 0)) ++copies[static_cast<std::size_t>(x)];
  for (std::size_t i = 0; i < copies.size(); ++i) {
    ASSERT_GE(static_cast<double>(copies[i]),
              std::floor(3000.0 * std::exp(double{logw[i]}) - 1e-5));
  }
}

}  // namespace
}  // namespace mote
