// The beams' correlation along a scan and the likelihood exponent it calls for (calibrate.hpp,
// BeamCorrelation): the effective number of independent beams of a scan by the initial
// positive sequence of the range errors' autocorrelation (Geyer 1992, "Practical Markov chain
// Monte Carlo", sec. 3.3), the tempering of Thrun et al., section 6.3.4, as its share of them.
#include <algorithm>
#include <cmath>
#include <string>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"

namespace mote::calibrate {
namespace {

constexpr std::size_t kMinPairs = 100;  // lag-1 pairs of hits
constexpr double kHitWindow = 3.0;      // sigma_hit: a reading the Gaussian placed
constexpr double kMinTempering = 0.01;

struct Hit {
  std::size_t scan, slot;
  double error;  // z - z*, m
};

std::vector<Hit> hits(const std::vector<BeamSample>& samples, double range_max, double sigma) {
  std::vector<Hit> out;
  for (const BeamSample& s : samples) {
    const double e = s.measured - s.expected;
    if (s.measured < range_max && s.expected < range_max && std::abs(e) < kHitWindow * sigma) {
      out.push_back({s.scan, s.slot, e});
    }
  }
  return out;
}

// Sums of centred products of the hits k slots apart in one scan, k = 1..max_lag. The samples
// come scan by scan with their slots rising, so the partners of a hit follow it.
struct LagSums {
  std::vector<double> product;
  std::vector<std::size_t> pairs;
};

LagSums lag_sums(const std::vector<Hit>& h, double mean, std::size_t max_lag) {
  LagSums s{std::vector<double>(max_lag + 2, 0.0), std::vector<std::size_t>(max_lag + 2, 0)};
  for (std::size_t i = 0; i < h.size(); ++i) {
    for (std::size_t j = i + 1; j < h.size() && h[j].scan == h[i].scan; ++j) {
      const std::size_t lag = h[j].slot - h[i].slot;
      if (lag > max_lag) break;
      s.product[lag] += (h[i].error - mean) * (h[j].error - mean);
      ++s.pairs[lag];
    }
  }
  return s;
}

}  // namespace

BeamCorrelation fit_beam_correlation(const std::vector<BeamSample>& samples, double range_max,
                                     double sigma_hit) {
  const std::vector<Hit> h = hits(samples, range_max, sigma_hit);
  double mean = 0;
  for (const Hit& x : h) mean += x.error;
  mean /= std::max<double>(1.0, static_cast<double>(h.size()));
  double var = 0;
  for (const Hit& x : h) var += (x.error - mean) * (x.error - mean);
  var /= std::max<double>(1.0, static_cast<double>(h.size()));
  // Lags up to half a scan: beyond it a pair spans more than half the field of view, and the
  // few pairs there are would be the same walls seen from the two ends.
  std::size_t slots = 1;
  for (const Hit& x : h) slots = std::max(slots, x.slot + 1);
  const std::size_t max_lag = std::max<std::size_t>(1, slots / 2);
  const LagSums s = lag_sums(h, mean, max_lag);
  BeamCorrelation c;
  c.pairs = s.pairs[1];
  if (c.pairs < kMinPairs || !(var > 0)) {
    throw Error("beam correlation fit: " + std::to_string(c.pairs) +
                " neighbouring hits, at least " + std::to_string(kMinPairs) + " needed");
  }
  std::vector<double> rho(max_lag + 2, 0.0);
  for (std::size_t k = 1; k <= max_lag; ++k) {
    rho[k] = s.pairs[k] > 0 ? s.product[k] / (static_cast<double>(s.pairs[k]) * var) : 0.0;
  }
  // Initial positive sequence: the pair sums rho_k + rho_k+1 of an autocorrelation are positive
  // until noise takes over; the first that is not ends the sum.
  double sum = 0;
  for (std::size_t k = 1; k <= max_lag && rho[k] + rho[k + 1] > 0; ++k) {
    sum += rho[k];
    c.rho.push_back(rho[k]);
  }
  c.tempering = std::clamp(1.0 / (1.0 + 2.0 * std::max(sum, 0.0)), kMinTempering, 1.0);
  return c;
}

}  // namespace mote::calibrate
