// Adaptive tempering: the ESS of tempered weights against a direct double computation, the
// exponent the search picks, and thread-count independence.
#include "mote/engine/tempering.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mote/engine/executor.hpp"
#include "mote/engine/philox.hpp"

namespace mote {
namespace {

// Normalized prior log-weights and Gaussian-ish log-likelihoods of spread `scale` nats.
struct Columns {
  std::vector<float> logw;
  std::vector<float> loglik;
};

Columns make_columns(std::size_t n, double scale) {
  Columns c{std::vector<float>(n), std::vector<float>(n)};
  const RngStream rng{3, 1, RngPurpose::kMotion};
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto z = rng.normal4(static_cast<std::uint32_t>(i));
    c.logw[i] = 0.3F * z[0];
    c.loglik[i] = static_cast<float>(-scale * z[1] * z[1]);
    total += std::exp(double(c.logw[i]));
  }
  for (float& v : c.logw) v -= static_cast<float>(std::log(total));
  return c;
}

double direct_ess(const Columns& c, double tau) {
  double w = 0.0;
  double w2 = 0.0;
  for (std::size_t i = 0; i < c.logw.size(); ++i) {
    const double e = std::exp(double(c.logw[i]) + tau * double(c.loglik[i]));
    w += e;
    w2 += e * e;
  }
  return w * w / w2;
}

TEST(TemperedEss, MatchesTheDirectSum) {
  const Columns c = make_columns(10000, 50.0);
  for (const float tau : {0.0F, 0.01F, 0.1F, 1.0F}) {
    const double ess = tempered_ess(c.logw.data(), c.loglik.data(), c.logw.size(), tau);
    EXPECT_NEAR(ess, direct_ess(c, tau), 1e-5 * direct_ess(c, tau)) << tau;
  }
}

TEST(TemperedEss, IgnoresNaNAndReportsZeroWhenNothingWeighs) {
  std::vector<float> logw{0.0F, std::nanf(""), 0.0F};
  std::vector<float> loglik{0.0F, 0.0F, -INFINITY};
  EXPECT_DOUBLE_EQ(tempered_ess(logw.data(), loglik.data(), 3, 1.0F), 1.0);
  std::vector<float> none{-INFINITY, -INFINITY};
  EXPECT_EQ(tempered_ess(none.data(), none.data(), 2, 1.0F), 0.0);
}

TEST(ChooseTempering, LandsTheEssOnTheTarget) {
  const Columns c = make_columns(20000, 200.0);  // untempered, the ESS collapses
  const TemperingConfig config{.target_ess_fraction = 0.1, .tolerance = 0.1};
  const TemperingChoice choice =
      choose_tempering(c.logw.data(), c.loglik.data(), c.logw.size(), config);
  EXPECT_LT(choice.tau, 1.0);
  EXPECT_GT(choice.tau, config.min_tau);
  const double target = 0.1 * choice.ess_before;
  EXPECT_NEAR(choice.ess_after, target, 0.1 * target);
  EXPECT_NEAR(choice.ess_after, direct_ess(c, choice.tau), 1e-4 * choice.ess_after);
  EXPECT_LE(choice.trials, config.max_trials + 3);
}

TEST(ChooseTempering, KeepsThePlainProductWhenTheScanIsMild) {
  const Columns c = make_columns(5000, 0.01);
  const TemperingChoice choice = choose_tempering(c.logw.data(), c.loglik.data(), 5000, {});
  EXPECT_EQ(choice.tau, 1.0);
  EXPECT_EQ(choice.trials, 2);  // ESS(0) and ESS(1)
}

TEST(ChooseTempering, IsIndependentOfThreadsAndGrain) {
  const Columns c = make_columns(100000, 300.0);
  TemperingChoice one;
  TemperingChoice two;
  Executor(1)([&] { one = choose_tempering(c.logw.data(), c.loglik.data(), 100000, {}, 1 << 20); });
  Executor(2)([&] { two = choose_tempering(c.logw.data(), c.loglik.data(), 100000, {}, 256); });
  EXPECT_EQ(one.tau, two.tau);
  EXPECT_EQ(one.ess_after, two.ess_after);
  EXPECT_EQ(one.trials, two.trials);
}

}  // namespace
}  // namespace mote
