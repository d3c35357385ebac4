#pragma once
/// \file
/// KLD-adaptive sample size (Fox, "Adapting the sample size in particle filters through
/// KLD-sampling", IJRR 2003): the number of particles n such that, with probability 1 - delta,
/// the KL divergence between the particle approximation and the true posterior stays below eps,
/// given k occupied histogram bins. Bins are counted with a dense bitset over the map region, in
/// time proportional to the particles.

#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "mote/core/free_space.hpp"
#include "mote/engine/chunks.hpp"
#include "mote/engine/particles.hpp"

namespace mote {

/// KLD-sampling parameters (defaults as ROS amcl).
struct KldConfig {
  double epsilon = 0.05;  ///< kld_err: bound on the KL divergence
  double delta = 0.01;    ///< probability that the bound is exceeded (z = quantile(1 - delta))
  /// ROS amcl compatibility: when true, `z` below is used directly (amcl's kld_z / pf_z).
  bool use_z = false;
  double z = 0.99;                                   ///< upper standard normal quantile when use_z
  double bin_x = 0.5;                                ///< m
  double bin_y = 0.5;                                ///< m
  double bin_theta = 10.0 * std::numbers::pi / 180;  ///< rad
  std::size_t min_particles = 500;                   ///< lower bound on n
  std::size_t max_particles = 5000;                  ///< upper bound on n
};

/// The standard normal quantile Phi^-1(p) for p in (0, 1) (Acklam's rational approximation,
/// relative error 1.15e-9, refined by one Halley step on erfc).
[[nodiscard]] double standard_normal_quantile(double p);

/// The chi-square quantile with `dof` degrees of freedom at the standard normal quantile z, by
/// Wilson and Hilferty (1931): dof (1 - 2/(9 dof) + z sqrt(2/(9 dof)))^3. Zero or negative
/// where the approximation breaks down (dof below about 2 with z well below 0).
[[nodiscard]] double chi_square_quantile(double dof, double z);

/// Fox 2003, eq. 13 (Wilson-Hilferty): n = (k-1)/(2 eps) (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) z)^3,
/// rounded up, then clamped to [min_particles, max_particles]; k <= 1 gives min_particles.
[[nodiscard]] std::size_t kld_sample_count(std::size_t k, const KldConfig& config);

/// A dense bitset of (x, y, theta) histogram bins over a bounded region; particles outside the
/// region fall in the nearest border bin, and a NaN coordinate in bin 0 of its axis. Allocation
/// happens in the constructor only.
class KldBins {
 public:
  /// Throws ConfigError unless the bin sizes are positive and finite, the region finite and
  /// non-empty, and the grid at most 2^32 bins.
  KldBins(const Bounds2& region, double bin_x, double bin_y, double bin_theta);

  /// Number of distinct bins occupied by the particles (weights ignored). Deterministic: bits
  /// are set with atomic OR, whose result does not depend on order, then counted by a reduce.
  [[nodiscard]] std::size_t count(const ConstParticleView& particles,
                                  std::size_t grain = kDefaultGrain);

  /// Number of distinct bins occupied by the particles that a systematic draw of n_out
  /// (resample_systematic with the same seed and step) copies at least once: the k of Fox's
  /// sequential rule for that draw. The store's weights must be normalized.
  [[nodiscard]] std::size_t count_drawn(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                                        std::uint64_t step, std::size_t grain = kDefaultGrain);

  /// The bin index of a pose (for tests and clustering).
  [[nodiscard]] std::uint64_t bin_of(float x, float y, float theta) const noexcept;
  /// Number of bins along x, y and theta.
  [[nodiscard]] std::size_t nx() const noexcept { return nx_; }
  [[nodiscard]] std::size_t ny() const noexcept { return ny_; }
  [[nodiscard]] std::size_t ntheta() const noexcept { return nt_; }

 private:
  template <class Keep>
  std::size_t count_where(const ConstParticleView& particles, const Keep& keep, std::size_t grain);
  /// Zeroes every bit the particles can have set (the whole bitset when that is cheaper).
  void clear(const ConstParticleView& particles, std::size_t grain);

  Bounds2 region_;
  float inv_x_, inv_y_, inv_t_;
  std::size_t nx_, ny_, nt_;
  std::vector<std::uint64_t> words_;
};

/// k from the bins occupied by the current particles (the support of the weighted set), then n
/// from kld_sample_count (no bin count when min_particles == max_particles: n is that count).
/// An upper bound of Fox's count; kld_draw_count is the rule itself.
[[nodiscard]] std::size_t kld_sample_count(const ConstParticleView& particles, KldBins& bins,
                                           const KldConfig& config,
                                           std::size_t grain = kDefaultGrain);

/// Fox's sequential rule on systematic draws (kld.cpp): the smallest n in the sequence
/// n_0 = min_particles, n_{r+1} = kld_sample_count(k(n_r)) with n >= kld_sample_count(k(n)),
/// where k(n) = bins.count_drawn(store, n, seed, step); within [min_particles, max_particles].
/// The store's weights must be normalized. Deterministic for any thread count and grain.
[[nodiscard]] std::size_t kld_draw_count(ParticleStore& store, KldBins& bins,
                                         const KldConfig& config, std::uint64_t seed,
                                         std::uint64_t step, std::size_t grain = kDefaultGrain);

/// KLD-sampling: n = kld_draw_count(...) and then resample_systematic(store, n, seed, step,
/// grain), whose ancestors are exactly the ones the count saw. Returns n.
std::size_t resample_kld_systematic(ParticleStore& store, KldBins& bins, const KldConfig& config,
                                    std::uint64_t seed, std::uint64_t step,
                                    std::size_t grain = kDefaultGrain);

}  // namespace mote
