// The batched beam-model likelihood (add_beam_log_likelihoods) against the scalar double
// formula beam_log_likelihood, term by term and summed over scans.
//
// Tolerance: the float path keeps every factor of the mixture within a few float ulp (2^-24 =
// 6e-8 each; its polynomials are within 2e-7), so each beam's log-likelihood is within
// 1e-6 * (1 + |log p|) of the double one (observed: 1.4e-7), and a scan's sum within
// 1e-6 * sum_b (1 + |log p_b|). The scan test also holds the sum to issue 7's target, 1e-5 of
// itself (observed: 2e-6, most of it float's rounding of logw).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/engine/beam_model.hpp"

namespace mote {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Case {
  MixtureParams mixture;
  float range_max;
};

// Mixtures that exercise every term: amcl's defaults; Thrun's proportions on the Intel
// scanner's range; no z_rand and no z_short (the float range loses far Gaussian tails, so those
// lanes take the double formula); z_max < 12 sigma (both tails of eq. 6.6 at once); a sharp
// Gaussian, a steep short exponential and z_max = 0 (log p_max = -inf).
std::vector<Case> cases() {
  return {
      {{}, 30.0F},
      {{.z_hit = 0.7,
        .z_short = 0.1,
        .z_max = 0.05,
        .z_rand = 0.15,
        .sigma_hit = 0.05,
        .lambda_short = 0.5},
       81.83F},
      {{.z_hit = 0.95,
        .z_short = 0.0,
        .z_max = 0.05,
        .z_rand = 0.0,
        .sigma_hit = 0.1,
        .lambda_short = 1.0},
       10.0F},
      {{.z_hit = 0.6,
        .z_short = 0.2,
        .z_max = 0.1,
        .z_rand = 0.1,
        .sigma_hit = 0.5,
        .lambda_short = 2.0},
       4.0F},
      {{.z_hit = 0.5,
        .z_short = 0.3,
        .z_max = 0.0,
        .z_rand = 0.2,
        .sigma_hit = 0.01,
        .lambda_short = 20.0},
       5.6F},
  };
}

float above(float x) { return std::nextafter(x, kInf); }
float below(float x) { return std::nextafter(x, -kInf); }

// Readings: 0, short, long, either side of the 6 sigma boundaries, just below z_max, max-range
// and beyond, and invalid ones (negative, NaN).
std::vector<float> readings(const Case& c) {
  const auto r = c.range_max;
  const auto six_sigma = static_cast<float>(6.0 * c.mixture.sigma_hit);
  return {0.0F,          1e-6F,
          0.3F * r,      0.5F * r,
          six_sigma,     below(six_sigma),
          r - six_sigma, above(r - six_sigma),
          below(r),      r,
          r + 5.0F,      kInf,
          -1.0F,         kNaN};
}

// Expected ranges: 0 (sensor inside a wall), tiny, the 6 sigma boundaries and their
// neighbours, around the reading z, near and at z_max, then uniform ones; and the values a
// caster never returns but the formula must survive (NaN, negative, beyond z_max).
std::vector<float> expected_ranges(const Case& c, float z, std::mt19937& rng) {
  const auto r = c.range_max;
  const auto sigma = static_cast<float>(c.mixture.sigma_hit);
  const float six_sigma = 6.0F * sigma;
  std::vector<float> out = {0.0F,
                            1e-30F,
                            1e-6F,
                            1e-3F,
                            six_sigma,
                            below(six_sigma),
                            above(six_sigma),
                            r - six_sigma,
                            below(r - six_sigma),
                            above(r - six_sigma),
                            below(r),
                            r,
                            kNaN,
                            -0.5F,
                            r + 1.0F};
  if (std::isfinite(z) && z >= 0.0F && z < r) {
    for (const float k : {-3.0F, -1.0F, -0.1F, 0.0F, 0.1F, 1.0F, 3.0F, 20.0F}) {
      out.push_back(std::clamp(z + k * sigma, 0.0F, r));
    }
  }
  std::uniform_real_distribution<float> u(0.0F, r);
  while (out.size() < 200) out.push_back(u(rng));
  return out;
}

// One beam, every z* as its own particle: logw[i] becomes the float path's log p(z | z*_i).
std::vector<float> batched_one_beam(const Case& c, float z, const std::vector<float>& z_star) {
  std::vector<float> logw(z_star.size(), 0.0F);
  const float ranges[] = {z};
  add_beam_log_likelihoods(ranges, c.range_max, z_star, {.mixture = c.mixture}, logw);
  return logw;
}

void expect_close(double batched, double exact, double tolerance, const char* what) {
  if (!std::isfinite(exact)) {
    // -inf (every term 0) and NaN (NaN z*) must come out exactly so.
    EXPECT_TRUE(batched == exact || (std::isnan(batched) && std::isnan(exact)))
        << what << ": " << batched << " instead of " << exact;
    return;
  }
  EXPECT_NEAR(batched, exact, tolerance) << what;
}

TEST(BeamLikelihoodBatched, EveryBeamMatchesTheScalarFormula) {
  std::mt19937 rng(3);
  for (const Case& c : cases()) {
    for (const float z : readings(c)) {
      const std::vector<float> z_star = expected_ranges(c, z, rng);
      const std::vector<float> batched = batched_one_beam(c, z, z_star);
      for (std::size_t i = 0; i < z_star.size(); ++i) {
        const double exact = beam_log_likelihood(z, z_star[i], c.range_max, c.mixture);
        SCOPED_TRACE(testing::Message()
                     << "z_max " << c.range_max << ", sigma " << c.mixture.sigma_hit << ", z " << z
                     << ", z* " << z_star[i]);
        expect_close(batched[i], exact, 1e-6 * (1.0 + std::abs(exact)), "log p(z | z*)");
      }
    }
  }
}

// A scan of 60 beams: the true ranges, and readings mostly at them, every tenth one short of
// them, some at max range.
struct Scan {
  std::vector<float> truth;
  std::vector<float> z;
};

Scan scan_of(const Case& c, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0F, 1.0F);
  Scan scan;
  for (std::size_t b = 0; b < 60; ++b) {
    const float truth = c.range_max * u(rng);
    scan.truth.push_back(truth);
    scan.z.push_back(b % 15 == 7 ? c.range_max : (b % 10 == 3 ? truth * u(rng) : truth));
  }
  return scan;
}

TEST(BeamLikelihoodBatched, ScanSumsMatchTheScalarLoopWithTempering) {
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0.0F, 1.0F);
  const double tau = 0.3;
  for (const Case& c : cases()) {
    const Scan scan = scan_of(c, rng);
    const std::vector<float>& z = scan.z;
    // Particles around the truth, two full blocks of 128 and a padded one.
    const std::size_t particles = 333;
    std::vector<float> z_star(particles * z.size());
    for (std::size_t i = 0; i < z_star.size(); ++i) {
      const float spread = static_cast<float>(c.mixture.sigma_hit) * noise(rng);
      z_star[i] = std::clamp(scan.truth[i % z.size()] + spread, 0.0F, c.range_max);
    }
    std::vector<float> logw(particles, -2.5F);
    add_beam_log_likelihoods(z, c.range_max, z_star, {.mixture = c.mixture, .tempering = tau},
                             logw);
    for (std::size_t p = 0; p < particles; ++p) {
      double sum = 0.0;
      double scale = 0.0;  // sum of (1 + |log p_b|): the per-beam bounds added up
      for (std::size_t b = 0; b < z.size(); ++b) {
        const double term =
            beam_log_likelihood(z[b], z_star[p * z.size() + b], c.range_max, c.mixture);
        sum += term;
        scale += 1.0 + std::abs(term);
      }
      SCOPED_TRACE(testing::Message() << "z_max " << c.range_max << ", particle " << p);
      if (!std::isfinite(sum)) {
        expect_close(logw[p], -2.5 + tau * sum, 0.0, "scan log-likelihood");
        continue;
      }
      // What the call added, against tau times the scalar sum; logw is float, so its two
      // roundings (tau * sum, then the addition) come on top of the float path's bound.
      const double added = logw[p] + 2.5;
      const double rounding = 6e-8 * (std::abs(tau * sum) + std::abs(logw[p]));
      expect_close(added, tau * sum, tau * 1e-6 * scale + rounding, "scan log-likelihood");
      EXPECT_LE(std::abs(added - tau * sum), 1e-5 * std::abs(tau * sum) + rounding);
    }
  }
}

TEST(BeamLikelihoodBatched, AParticlesResultDoesNotDependOnItsPlaceInTheBatch) {
  // Chunk boundaries move particles between blocks and lanes; the filter's bit-identical
  // results for any grain rest on this.
  const Case c = cases()[1];
  std::mt19937 rng(9);
  const std::vector<float> z = scan_of(c, rng).z;
  std::uniform_real_distribution<float> u(0.0F, c.range_max);
  std::vector<float> row(z.size());
  for (float& v : row) v = u(rng);
  row[4] = 0.0F;
  row[5] = 1e-3F;
  const auto weigh_at = [&](std::size_t index, std::size_t particles) {
    std::vector<float> z_star(particles * z.size());
    for (float& v : z_star) v = u(rng);
    std::copy(row.begin(), row.end(),
              z_star.begin() + static_cast<std::ptrdiff_t>(index * z.size()));
    std::vector<float> logw(particles, 0.0F);
    add_beam_log_likelihoods(z, c.range_max, z_star, {.mixture = c.mixture}, logw);
    return logw[index];
  };
  const float alone = weigh_at(0, 1);
  EXPECT_EQ(alone, weigh_at(77, 200));
  EXPECT_EQ(alone, weigh_at(130, 131));
  EXPECT_EQ(alone, weigh_at(255, 256));
}

TEST(BeamLikelihoodBatched, NonFinitePosesKeepTheScalarLoopsOutcome) {
  // A particle with a non-finite pose gets NaN expected ranges: like the scalar loop, its
  // log-weight becomes NaN, max-range readings included (p_hit at z_max needs z*).
  const Case c = cases()[0];
  const std::vector<float> nan_row(3, kNaN);
  std::vector<float> logw(1, 0.0F);
  const std::vector<float> mixed = {2.0F, c.range_max, 5.0F};
  add_beam_log_likelihoods(mixed, c.range_max, nan_row, {.mixture = c.mixture}, logw);
  EXPECT_TRUE(std::isnan(logw[0]));
  logw[0] = 0.0F;
  const std::vector<float> all_max(3, c.range_max);
  add_beam_log_likelihoods(all_max, c.range_max, nan_row, {.mixture = c.mixture}, logw);
  EXPECT_TRUE(std::isnan(logw[0]));
}

// Thrun eq. 6.12 at z = z_max, written out: z_max (p_max = 1) + z_hit p_hit(z_max) +
// z_short p_short(z_max); p_rand is 0 there (uniform on [0, z_max)).
double book_max_range_probability(double z_star, double z_max, const MixtureParams& p) {
  const double s = p.sigma_hit;
  const double mass = 0.5 * std::erfc(-(z_max - z_star) / (s * std::numbers::sqrt2)) -
                      0.5 * std::erfc(z_star / (s * std::numbers::sqrt2));
  const double d = (z_max - z_star) / s;
  const double p_hit = std::exp(-0.5 * d * d) / (s * std::sqrt(2.0 * std::numbers::pi)) / mass;
  const double l = p.lambda_short;
  const double p_short =
      z_max <= z_star ? l * std::exp(-l * z_max) / (1.0 - std::exp(-l * z_star)) : 0.0;
  return p.z_max + p.z_hit * p_hit + p.z_short * p_short;
}

TEST(BeamLikelihoodBatched, MaxRangeReadingsDependOnTheExpectedRange) {
  // A "no return" is likely for a particle whose ray reaches z_max and unlikely for one that
  // expects a wall 2 m away; readings beyond z_max (and +inf) are max-range readings too.
  for (const Case& c : cases()) {
    const float r = c.range_max;
    const std::vector<float> z_star = {2.0F, r - 0.5F, r - 0.1F, r - 0.01F, r};
    for (const float z : {r, r + 5.0F, kInf}) {
      const std::vector<float> batched = batched_one_beam(c, z, z_star);
      for (std::size_t i = 0; i < z_star.size(); ++i) {
        const double book = std::log(book_max_range_probability(z_star[i], r, c.mixture));
        SCOPED_TRACE(testing::Message() << "z_max " << r << ", z " << z << ", z* " << z_star[i]);
        expect_close(batched[i], book, 2e-6 * (1.0 + std::abs(book)), "log p(z_max | z*)");
      }
      EXPECT_GT(batched.back(), batched.front());
    }
  }
}

TEST(BeamLikelihoodBatched, ArraysOfTheWrongSizeAreAConfigError) {
  std::vector<float> logw(4, 0.0F);
  const std::vector<float> ranges = {1.0F, 2.0F};
  const std::vector<float> z_star(7, 1.0F);
  EXPECT_THROW(add_beam_log_likelihoods(ranges, 10.0F, z_star, {}, logw), ConfigError);
}

}  // namespace
}  // namespace mote
