// fit_beam_correlation (calibrate.hpp) on draws with a known correlation along the scan:
// independent range errors keep the plain product of the beams, errors that follow a
// first-order autoregression along the scan (rho_k = phi^k) call for 1 / (1 + 2 sum phi^k).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"

namespace mote::calibrate {
namespace {

constexpr double kRangeMax = 20.0;
constexpr double kSigma = 0.05;  // m, the errors' marginal spread
constexpr std::size_t kSlots = 60;

// `scans` scans of kSlots beams 5 m from a wall whose range errors follow e_k = phi e_k-1 +
// sqrt(1 - phi^2) n_k along the scan (marginal spread kSigma, rho_k = phi^k). Every tenth beam
// reads no return, which leaves a gap the fit must not bridge as a lag-1 pair.
std::vector<BeamSample> scans(std::size_t count, double phi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, kSigma);
  std::vector<BeamSample> out;
  for (std::size_t s = 0; s < count; ++s) {
    double e = n(rng);
    for (std::size_t k = 0; k < kSlots; ++k) {
      if (k > 0) e = phi * e + std::sqrt(1.0 - phi * phi) * n(rng);
      const double measured = k % 10 == 9 ? kRangeMax : 5.0 + e;
      out.push_back({measured, 5.0, s, k});
    }
  }
  return out;
}

double expected_tempering(double phi) {
  double sum = 0;
  for (std::size_t k = 1; k <= kSlots / 2; ++k) sum += std::pow(phi, static_cast<double>(k));
  return 1.0 / (1.0 + 2.0 * sum);
}

TEST(CalibrateCorrelation, IndependentErrorsKeepThePlainProduct) {
  const BeamCorrelation c = fit_beam_correlation(scans(800, 0.0, 1), kRangeMax, kSigma);
  EXPECT_GT(c.tempering, 0.9);
  EXPECT_LE(c.tempering, 1.0);
  // 48 lag-1 pairs a scan (59, less the 11 that touch a no-return), less the few beyond 3 sigma.
  EXPECT_LE(c.pairs, 800U * 48U);
  EXPECT_GT(c.pairs, 800U * 48U * 98 / 100);
}

TEST(CalibrateCorrelation, CorrelatedErrorsCallForTheEffectiveShare) {
  for (const double phi : {0.3, 0.5, 0.8}) {
    const BeamCorrelation c = fit_beam_correlation(scans(800, phi, 2), kRangeMax, kSigma);
    EXPECT_NEAR(c.tempering, expected_tempering(phi), 0.1 * expected_tempering(phi)) << phi;
    ASSERT_FALSE(c.rho.empty());
    EXPECT_NEAR(c.rho.front(), phi, 0.05) << phi;
  }
}

TEST(CalibrateCorrelation, TooFewNeighbouringHitsIsAnError) {
  EXPECT_THROW((void)fit_beam_correlation(scans(2, 0.5, 3), kRangeMax, kSigma), Error);
}

}  // namespace
}  // namespace mote::calibrate
