#include "mote/engine/weights.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mote/engine/executor.hpp"

namespace mote {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(Normalize, GivesLogSumExpEssAndMeanLikelihood) {
  ParticleStore store(4);
  const ParticleView p = store.view();
  // Weights about 1:2:3:4 at a scale where exp() alone would overflow even in double: the max
  // must be subtracted. Near 1000 a float log-weight has a resolution of 6e-5, so the expected
  // values are computed in double from the stored floats.
  for (std::size_t i = 0; i < 4; ++i) p.logw[i] = 1000.0F + std::log(static_cast<float>(i + 1));
  const std::vector<double> stored(p.logw, p.logw + 4);
  double sum = 0.0;
  for (const double v : stored) sum += std::exp(v - 1000.0);
  double sum_sq = 0.0;
  for (const double v : stored) sum_sq += std::pow(std::exp(v - 1000.0) / sum, 2);
  const NormalizeResult r = normalize(p);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.log_total, 1000.0 + std::log(sum), 1e-6);
  EXPECT_EQ(r.log_mean_likelihood, r.log_total);
  EXPECT_NEAR(r.effective_sample_size, 1.0 / sum_sq, 1e-5);
  EXPECT_NEAR(r.effective_sample_size, 1.0 / 0.3, 1e-3);  // 1 / (0.01 + 0.04 + 0.09 + 0.16)
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(std::exp(p.logw[i]), std::exp(stored[i] - 1000.0) / sum, 1e-6);
  }
  EXPECT_NEAR(effective_sample_size(p), 1.0 / sum_sq, 1e-5);
}

TEST(Normalize, MeanLikelihoodIsThePriorWeightedMean) {
  // Thrun table 8.3, line 8 with normalized prior weights w_prev: logw = log w_prev + log p(z|x),
  // and w_avg = sum_i w_prev,i p(z | x_i) (1/N sum p(z | x_i) for uniform priors).
  const double prior[] = {0.1, 0.2, 0.3, 0.4};
  const double likelihood[] = {2e-3, 5e-4, 1e-3, 4e-3};
  ParticleStore store(4);
  const ParticleView p = store.view();
  double w_avg = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    p.logw[i] = static_cast<float>(std::log(prior[i]) + std::log(likelihood[i]));
    w_avg += std::exp(static_cast<double>(p.logw[i]));
  }
  const NormalizeResult r = normalize(p);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.log_mean_likelihood, std::log(w_avg), 1e-6);
  // Uniform priors, as after resampling: the plain mean of the likelihoods.
  for (std::size_t i = 0; i < 4; ++i) {
    p.logw[i] = static_cast<float>(-std::log(4.0) + std::log(likelihood[i]));
  }
  const double mean = (2e-3 + 5e-4 + 1e-3 + 4e-3) / 4.0;
  EXPECT_NEAR(normalize(p).log_mean_likelihood, std::log(mean), 1e-6);
}

TEST(Normalize, AllMinusInfinityIsReportedAndNeverNaN) {
  for (const float bad : {-kInf, std::numeric_limits<float>::quiet_NaN()}) {
    ParticleStore store(1000);
    const ParticleView p = store.view();
    for (std::size_t i = 0; i < p.size(); ++i) p.logw[i] = bad;
    const NormalizeResult r = normalize(p);
    EXPECT_EQ(r.status, WeightStatus::kDegenerate);
    EXPECT_FALSE(r.ok());
    EXPECT_FALSE(std::isnan(r.log_mean_likelihood));
    EXPECT_EQ(r.effective_sample_size, 1000.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      ASSERT_FLOAT_EQ(p.logw[i], -std::log(1000.0F));  // documented: reset to uniform
    }
  }
}

TEST(Normalize, NaNWeightsCountAsZero) {
  ParticleStore store(3);
  const ParticleView p = store.view();
  p.logw[0] = std::numeric_limits<float>::quiet_NaN();
  p.logw[1] = -2.0F;
  p.logw[2] = -2.0F;
  ASSERT_TRUE(normalize(p).ok());
  EXPECT_EQ(p.logw[0], -kInf);
  EXPECT_NEAR(p.logw[1], std::log(0.5F), 1e-6);
  EXPECT_EQ(normalize(ParticleStore().view()).status, WeightStatus::kEmpty);
}

TEST(Normalize, IsIdenticalForAnyThreadCountAndGrain) {
  const auto run = [](int threads, std::size_t grain) {
    ParticleStore store(100003);
    const ParticleView p = store.view();
    for (std::size_t i = 0; i < p.size(); ++i) p.logw[i] = -0.001F * static_cast<float>(i % 977);
    const Executor ex(threads);
    NormalizeResult r;
    ex([&] { r = normalize(p, grain); });
    return std::pair{r.log_total, std::vector<float>(p.logw, p.logw + p.size())};
  };
  const auto reference = run(1, 1 << 20);
  for (const int threads : {1, 2, 4}) {
    for (const std::size_t grain : {std::size_t{16}, std::size_t{5000}}) {
      const auto other = run(threads, grain);
      EXPECT_EQ(other.first, reference.first) << threads << " " << grain;
      EXPECT_EQ(other.second, reference.second) << threads << " " << grain;
    }
  }
}

TEST(Reweight, AddsTemperedLogLikelihoods) {
  ParticleStore store(100);
  const ParticleView p = store.view();
  for (std::size_t i = 0; i < p.size(); ++i) p.x[i] = static_cast<float>(i);
  const std::vector<float> before(p.logw, p.logw + p.size());
  reweight(
      p, [](float x, float, float) { return -0.5 * x; }, 0.5, 16);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_FLOAT_EQ(p.logw[i], before[i] - 0.25F * static_cast<float>(i));
  }
}

TEST(Reweight, ChunkCallbacksCoverEachParticleOnce) {
  ParticleStore store(1000);
  const ParticleView p = store.view();
  std::fill_n(p.logw, p.size(), 0.0F);
  const Executor ex(2);
  ex([&] {
    reweight_chunks(
        p,
        [](const ParticleView& v, std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) v.logw[i] += 1.0F;
        },
        32);
  });
  for (std::size_t i = 0; i < p.size(); ++i) ASSERT_EQ(p.logw[i], 1.0F);
}

TEST(ResamplePolicy, ResamplesBelowTheEssFraction) {
  EXPECT_TRUE(should_resample(49.0, 100));
  EXPECT_FALSE(should_resample(50.0, 100));
  EXPECT_TRUE(should_resample(79.0, 100, 0.8));
}

}  // namespace
}  // namespace mote
