// The sensor model's intrinsic parameters from beams at known poses: the beam mixture by
// Thrun et al.'s expectation-maximization (Probabilistic Robotics, table 6.2, section 6.3.2) and
// the likelihood field's mixture by maximum likelihood on the endpoint distances (table 6.3).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"

namespace mote::calibrate {
namespace {

constexpr double kSigmaMin = 0.005;  // m: below the cell size of any map mote loads
constexpr double kSigmaMax = 5.0;    // m
constexpr double kLambdaMin = 1e-3;  // 1/m: a flat "short" component
constexpr double kLambdaMax = 50.0;  // 1/m: shorts within 2 cm of the sensor
constexpr double kWeightFloor = 1e-4;
constexpr int kMaxIterations = 300;
constexpr std::size_t kMinSamples = 100;

double normal_pdf(double x, double sigma) {
  return std::exp(-0.5 * x * x / (sigma * sigma)) / (std::sqrt(2.0 * std::numbers::pi) * sigma);
}

double normal_tail(double x) { return 0.5 * std::erfc(x / std::numbers::sqrt2); }

// Mass of the truncated exponential of eq. 6.7 at z, for an expected range zs (eq. 6.9's eta).
double short_density(double z, double zs, double lambda) {
  if (z > zs || zs <= 0.0) return 0.0;
  return lambda * std::exp(-lambda * z) / -std::expm1(-lambda * zs);
}

struct Responsibilities {
  double hit = 0, shrt = 0, max = 0, rand = 0, total = 0;
};

// E-step of table 6.2 for one beam (lines 4-9). The laser reports anything at or beyond
// range_max as range_max, so a no-return reading is a point mass: the max component (eq. 6.10)
// or a hit whose Gaussian spills past range_max (all of it when nothing is in range); below
// range_max the components are densities (eqs. 6.4, 6.7, 6.11).
Responsibilities e_step(const BeamSample& s, double range_max, const BeamMixture& p) {
  Responsibilities r;
  const bool no_wall = s.expected >= range_max;
  if (s.measured >= range_max) {
    const double spill = no_wall ? 1.0 : normal_tail((range_max - s.expected) / p.sigma_hit);
    r.hit = p.z_hit * spill;
    r.max = p.z_max;
  } else {
    r.hit = no_wall ? 0.0 : p.z_hit * normal_pdf(s.measured - s.expected, p.sigma_hit);
    r.shrt = p.z_short * short_density(s.measured, s.expected, p.lambda_short);
    r.rand = p.z_rand / range_max;
  }
  r.total = r.hit + r.shrt + r.max + r.rand;
  return r;
}

double beam_log_likelihood(const std::vector<BeamSample>& samples, double range_max,
                           const BeamMixture& p) {
  double sum = 0;
  for (const BeamSample& s : samples)
    sum += std::log(std::max(e_step(s, range_max, p).total, 1e-300));
  return sum;
}

// The exact M-step for lambda_short: the root of sum e_i (1/lambda - z_i - z*_i exp(-lambda
// z*_i) / (1 - exp(-lambda z*_i))) = 0, the derivative of the truncated exponential's
// log-likelihood, by bisection on log lambda (the sum falls monotonically in lambda).
double fit_lambda(const std::vector<BeamSample>& samples, const std::vector<double>& e_short) {
  auto slope = [&](double lambda) {
    double g = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (e_short[i] <= 0) continue;
      const double zs = samples[i].expected;
      const double tail = zs * std::exp(-lambda * zs) / -std::expm1(-lambda * zs);
      g += e_short[i] * (1.0 / lambda - samples[i].measured - tail);
    }
    return g;
  };
  double lo = std::log(kLambdaMin);
  double hi = std::log(kLambdaMax);
  if (slope(std::exp(lo)) <= 0) return kLambdaMin;
  if (slope(std::exp(hi)) >= 0) return kLambdaMax;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (slope(std::exp(mid)) > 0 ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

BeamMixture m_step(const std::vector<BeamSample>& samples, double range_max, const BeamMixture& p) {
  std::vector<double> e_short(samples.size(), 0.0);
  double hit = 0, shrt = 0, max = 0, rand = 0, hit_finite = 0, hit_sq = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const BeamSample& s = samples[i];
    const Responsibilities r = e_step(s, range_max, p);
    if (r.total <= 0) continue;
    const double eh = r.hit / r.total;
    hit += eh;
    e_short[i] = r.shrt / r.total;
    shrt += e_short[i];
    max += r.max / r.total;
    rand += r.rand / r.total;
    if (s.measured < range_max) {  // sigma from the readings the Gaussian placed (line 14)
      hit_finite += eh;
      hit_sq += eh * (s.measured - s.expected) * (s.measured - s.expected);
    }
  }
  const auto n = static_cast<double>(samples.size());
  BeamMixture q;
  q.z_hit = hit / n;  // table 6.2, lines 10-13
  q.z_short = shrt / n;
  q.z_max = max / n;
  q.z_rand = rand / n;
  q.sigma_hit = hit_finite > 0 ? std::clamp(std::sqrt(hit_sq / hit_finite), kSigmaMin, kSigmaMax)
                               : p.sigma_hit;
  q.lambda_short = shrt > 0 ? fit_lambda(samples, e_short) : p.lambda_short;
  return q;
}

void note_bound(FitQuality& q, const std::string& name, double v, double lo, double hi) {
  if (v <= lo * (1 + 1e-9))
    q.at_bound.push_back(name + " (lower bound " + std::to_string(lo) + ")");
  if (v >= hi * (1 - 1e-9))
    q.at_bound.push_back(name + " (upper bound " + std::to_string(hi) + ")");
}

void require_samples(std::size_t n, const char* what) {
  if (n < kMinSamples) {
    throw Error(std::string(what) + ": " + std::to_string(n) + " beams, at least " +
                std::to_string(kMinSamples) + " needed");
  }
}

}  // namespace

BeamFit fit_beam_mixture(const std::vector<BeamSample>& samples, double range_max,
                         BeamMixture start) {
  require_samples(samples.size(), "beam mixture fit");
  BeamFit fit{start, {}};
  fit.quality.samples = samples.size();
  double ll = beam_log_likelihood(samples, range_max, start);
  fit.quality.log_likelihood_before = ll;
  for (int it = 0; it < kMaxIterations; ++it) {
    fit.params = m_step(samples, range_max, fit.params);
    const double next = beam_log_likelihood(samples, range_max, fit.params);
    fit.quality.iterations = it + 1;
    const bool done = std::abs(next - ll) < 1e-7 * static_cast<double>(samples.size());
    ll = next;
    if (done) break;
  }
  fit.quality.log_likelihood_after = ll;
  const BeamMixture& p = fit.params;
  note_bound(fit.quality, "sigma_hit", p.sigma_hit, kSigmaMin, kSigmaMax);
  note_bound(fit.quality, "lambda_short", p.lambda_short, kLambdaMin, kLambdaMax);
  note_bound(fit.quality, "z_short", std::max(p.z_short, kWeightFloor), kWeightFloor, 1.0);
  note_bound(fit.quality, "z_max", std::max(p.z_max, kWeightFloor), kWeightFloor, 1.0);
  note_bound(fit.quality, "z_rand", std::max(p.z_rand, kWeightFloor), kWeightFloor, 1.0);
  return fit;
}

FieldFit fit_likelihood_field(const std::vector<double>& distances, double range_max,
                              FieldMixture start) {
  require_samples(distances.size(), "likelihood field fit");
  const double uniform = 1.0 / range_max;
  auto log_likelihood = [&](const FieldMixture& p) {
    double sum = 0;
    for (double d : distances) {
      sum += std::log(p.z_hit * normal_pdf(d, p.sigma_hit) + p.z_rand * uniform);
    }
    return sum;
  };
  FieldFit fit{start, {}};
  fit.quality.samples = distances.size();
  double ll = log_likelihood(start);
  fit.quality.log_likelihood_before = ll;
  for (int it = 0; it < kMaxIterations; ++it) {
    // EM for the two-part mixture: responsibilities of the Gaussian, then its share and spread.
    double share = 0, sq = 0;
    for (double d : distances) {
      const double h = fit.params.z_hit * normal_pdf(d, fit.params.sigma_hit);
      const double r = h / (h + fit.params.z_rand * uniform);
      share += r;
      sq += r * d * d;
    }
    const auto n = static_cast<double>(distances.size());
    fit.params.z_hit = std::clamp(share / n, kWeightFloor, 1.0 - kWeightFloor);
    fit.params.z_rand = 1.0 - fit.params.z_hit;
    fit.params.sigma_hit =
        share > 0 ? std::clamp(std::sqrt(sq / share), kSigmaMin, kSigmaMax) : fit.params.sigma_hit;
    const double next = log_likelihood(fit.params);
    fit.quality.iterations = it + 1;
    const bool done = std::abs(next - ll) < 1e-7 * n;
    ll = next;
    if (done) break;
  }
  fit.quality.log_likelihood_after = ll;
  note_bound(fit.quality, "sigma_hit", fit.params.sigma_hit, kSigmaMin, kSigmaMax);
  note_bound(fit.quality, "z_rand", fit.params.z_rand, kWeightFloor, 1.0 - kWeightFloor);
  note_bound(fit.quality, "z_hit", fit.params.z_hit, kWeightFloor, 1.0 - kWeightFloor);
  return fit;
}

}  // namespace mote::calibrate
