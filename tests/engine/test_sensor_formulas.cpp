// The beam and likelihood-field formulas against a direct transcription of Thrun et al.,
// tables 6.1-6.3, whose normalizers are integrated numerically instead of through erfc.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mote/engine/sensor_model.hpp"

namespace mote {
namespace {

double gaussian(double x, double mean, double sigma) {
  const double d = (x - mean) / sigma;
  return std::exp(-0.5 * d * d) / (sigma * std::sqrt(2.0 * std::numbers::pi));
}

// eq. 6.6 by the trapezoid rule over [0, z_max].
double integral_of_gaussian(double mean, double sigma, double z_max) {
  const int n = 200000;
  const double h = z_max / n;
  double sum = 0.5 * (gaussian(0.0, mean, sigma) + gaussian(z_max, mean, sigma));
  for (int i = 1; i < n; ++i) sum += gaussian(i * h, mean, sigma);
  return sum * h;
}

// Table 6.1 / eq. 6.12 term by term, with the supports of eqs. 6.4-6.11 as the book states them:
// p_hit on 0 <= z <= z_max, p_short on 0 <= z <= z*, p_max at z = z_max, p_rand on
// 0 <= z < z_max. A reading beyond z_max is the sensor's "no return", i.e. z = z_max.
double book_beam_probability(double z, double z_star, double z_max, const MixtureParams& p) {
  if (z > z_max) z = z_max;
  double p_hit = 0.0;
  double p_short = 0.0;
  double p_max = 0.0;
  double p_rand = 0.0;
  if (z >= 0.0 && z <= z_max) {
    p_hit = gaussian(z, z_star, p.sigma_hit) / integral_of_gaussian(z_star, p.sigma_hit, z_max);
  }
  if (z >= 0.0 && z < z_max) p_rand = 1.0 / z_max;
  if (z >= 0.0 && z <= z_star) {
    p_short =
        p.lambda_short * std::exp(-p.lambda_short * z) / (1.0 - std::exp(-p.lambda_short * z_star));
  }
  if (z == z_max) p_max = 1.0;
  return p.z_hit * p_hit + p.z_short * p_short + p.z_max * p_max + p.z_rand * p_rand;
}

TEST(BeamLogLikelihood, MatchesTheBookOnHandBuiltCases) {
  const MixtureParams p{.z_hit = 0.7,
                        .z_short = 0.1,
                        .z_max = 0.05,
                        .z_rand = 0.15,
                        .sigma_hit = 0.2,
                        .lambda_short = 0.5};
  const double z_max = 10.0;
  struct Case {
    double z;
    double z_star;
  };
  // Centre of the range, short readings, long readings, near 0 and near z_max (where the
  // Gaussian's normalizer differs from 1), and max-range readings: far from the expected range,
  // near it (p_hit at z_max), at it (p_short at z_max too) and beyond z_max.
  for (const Case c : {Case{5.0, 5.0}, Case{3.0, 5.0}, Case{5.3, 5.0}, Case{0.1, 0.2},
                       Case{9.9, 9.95}, Case{0.0, 0.05}, Case{10.0, 4.0}, Case{7.0, 2.0},
                       Case{10.0, 9.9}, Case{10.0, 9.5}, Case{10.0, 10.0}, Case{12.0, 9.8}}) {
    const double expected = std::log(book_beam_probability(c.z, c.z_star, z_max, p));
    EXPECT_NEAR(beam_log_likelihood(c.z, c.z_star, z_max, p), expected, 1e-6)
        << "z = " << c.z << ", z* = " << c.z_star;
  }
}

TEST(BeamLogLikelihood, IntegratesToOneOverTheRange) {
  // p(z | z*) is a density on [0, z_max) plus the point mass z_max at z_max.
  const MixtureParams p{.z_hit = 0.6,
                        .z_short = 0.2,
                        .z_max = 0.1,
                        .z_rand = 0.1,
                        .sigma_hit = 0.3,
                        .lambda_short = 0.4};
  const double z_max = 8.0;
  const int n = 400000;
  const double h = z_max / n;
  double mass = 0.0;
  for (int i = 0; i < n; ++i) mass += std::exp(beam_log_likelihood((i + 0.5) * h, 3.0, z_max, p));
  mass *= h;
  mass += std::exp(beam_log_likelihood(z_max, 3.0, z_max, p));
  EXPECT_NEAR(mass, 1.0, 1e-4);
}

TEST(BeamLogLikelihood, MaxRangeReadingPenalizesAParticleThatExpectsANearWall) {
  // A "no return" is likelier for a particle whose ray reaches z_max than for one expecting a
  // wall 2 m away (Thrun eq. 6.12 at z = z_max; amcl's beam model adds p_hit and p_short there
  // too): the difference is z_hit p_hit + z_short p_short of the far particle.
  const MixtureParams p;  // amcl's defaults
  const double z_max = 10.0;
  const double far = beam_log_likelihood(z_max, z_max, z_max, p);
  const double near_wall = beam_log_likelihood(z_max, 2.0, z_max, p);
  EXPECT_NEAR(near_wall, std::log(p.z_max), 1e-9);  // p_hit(z_max; 2 m) is 1e-174
  EXPECT_GT(far - near_wall, 1.0);
  EXPECT_NEAR(far, std::log(book_beam_probability(z_max, z_max, z_max, p)), 1e-6);
}

TEST(BeamLogLikelihood, StaysFiniteForASensorTouchingAWall) {
  // z* a hair above 0: eq. 6.9's normalizer 1 / (1 - exp(-lambda z*)) is about 1 / (lambda z*),
  // large but finite, and the short-reading density z_short / z* with it.
  MixtureParams p;
  const double log_short = std::log(p.z_short / 1e-30);
  EXPECT_NEAR(beam_log_likelihood(0.0, 1e-30, 10.0, p), log_short, 1e-9 * log_short);
  p.z_short = 0.0;
  EXPECT_TRUE(std::isfinite(beam_log_likelihood(0.0, 1e-30, 10.0, p)));
}

TEST(LikelihoodFieldDensity, IsTheBooksMixture) {
  const MixtureParams p{.z_hit = 0.8, .z_rand = 0.2, .sigma_hit = 0.1};
  for (double d : {0.0, 0.05, 0.1, 0.3, 2.0}) {
    EXPECT_NEAR(likelihood_field_density(d, 20.0, p), 0.8 * gaussian(d, 0.0, 0.1) + 0.2 / 20.0,
                1e-12);
  }
}

TEST(AmclLikelihoodFieldPz, IsAmclsUnnormalizedGaussian) {
  const MixtureParams p{.z_hit = 0.5, .z_rand = 0.5, .sigma_hit = 0.2};
  EXPECT_NEAR(amcl_likelihood_field_pz(0.0, 10.0, p), 0.5 + 0.05, 1e-12);
  EXPECT_NEAR(amcl_likelihood_field_pz(0.2, 10.0, p), 0.5 * std::exp(-0.5) + 0.05, 1e-12);
}

}  // namespace
}  // namespace mote
