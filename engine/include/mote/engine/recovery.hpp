#pragma once
/// \file
/// Initialization (around a pose, or uniform over free space for global localization) and
/// recovery from localization failure by augmented MCL (Thrun et al., table 8.3).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "mote/core/free_space.hpp"
#include "mote/core/pose.hpp"
#include "mote/engine/chunks.hpp"
#include "mote/engine/particles.hpp"

namespace mote {

/// Augmented MCL smoothing rates (ROS amcl recovery_alpha_slow / recovery_alpha_fast; 0 and 0
/// disable recovery). Requires 0 <= alpha_slow << alpha_fast <= 1.
struct AugmentedMclConfig {
  double alpha_slow = 0.001;  ///< long-term average rate
  double alpha_fast = 0.1;    ///< short-term average rate
};

/// The long- and short-term averages of the measurement likelihood, w_slow and w_fast, kept in
/// the log domain so that likelihoods of many beams (far below 1e-300) do not underflow.
class AugmentedMcl {
 public:
  explicit AugmentedMcl(AugmentedMclConfig config = {}) : config_(config) {}

  /// Table 8.3, lines 10-11: w_slow += alpha_slow (w_avg - w_slow), same for w_fast, where
  /// w_avg = exp(log_mean_likelihood) (NormalizeResult::log_mean_likelihood). The first call
  /// sets both to w_avg (as amcl does). A degenerate update (-inf) pulls both towards 0, which
  /// raises the injection probability: that is how recovery takes over.
  void update(double log_mean_likelihood) noexcept;

  /// Table 8.3, line 13: max(0, 1 - w_fast / w_slow), the probability
  /// of replacing a particle by a random one; 0 before the first update and when recovery is
  /// disabled.
  [[nodiscard]] double injection_probability() const noexcept;

  /// False when the config disables recovery (an alpha of 0): update() is then not needed.
  [[nodiscard]] bool enabled() const noexcept {
    return config_.alpha_slow > 0.0 && config_.alpha_fast > 0.0;
  }
  [[nodiscard]] double log_w_slow() const noexcept { return log_slow_; }
  [[nodiscard]] double log_w_fast() const noexcept { return log_fast_; }
  /// Forgets the averages (e.g. after a manual re-initialization).
  void reset() noexcept { started_ = false; }

 private:
  AugmentedMclConfig config_;
  double log_slow_ = 0.0;
  double log_fast_ = 0.0;
  bool started_ = false;
};

/// Replaces each particle, with probability `probability`, by a pose uniform over free space
/// (uniform free cell, uniform point in it, uniform heading). Decisions and poses are drawn per
/// particle index from Philox keyed by (seed, step, RngPurpose::kInjection / kFreePose), so the
/// result is independent of threads and grain. Log-weights are left as they are (call after
/// resampling, when they are uniform). Returns how many particles were replaced.
std::size_t inject_random_particles(const ParticleView& particles, double probability,
                                    const FreeSpace& space, std::uint64_t seed, std::uint64_t step,
                                    std::size_t grain = kDefaultGrain);

/// Injection into a weighted set, without resampling it (augmented MCL when resampling is
/// selective). Only particles whose normalized weight is at most the mean 1/N may be replaced
/// (all of them in a freshly resampled set), each with probability
/// min(1, probability * N / (number eligible)), so that about
/// probability * N are; an injected particle gets the mean weight 1/N, and the weights are
/// renormalized. The set's mass thus moves from its weakest members to uniform free-space
/// poses, about as the book's (1 - p) posterior + p uniform mixture, while the hypotheses
/// that carry the weight survive until resampling can copy them: replacing particles
/// regardless of their weight would discard the evidence a right but young hypothesis has
/// gathered over a few updates. log-weights must be normalized. Deterministic (Philox keyed by
/// seed, step and index). Returns how many particles were replaced.
std::size_t inject_into_weighted(const ParticleView& particles, double probability,
                                 const FreeSpace& space, std::uint64_t seed, std::uint64_t step,
                                 std::size_t grain = kDefaultGrain);

/// A local search: appends n particles around `center` that carry 1 - kept of the belief, as
/// append_uniform() does: positions from N(center, radius^2 / 4) in x and y (95 % within
/// `radius`), headings uniform (a missed turn is any turn), from Philox keyed by seed, step and
/// RngPurpose::kLocalSearch. log-weights must be normalized; they are again afterwards.
void append_around(ParticleStore& store, std::size_t n, double kept, const Pose2& center,
                   double radius, std::uint64_t seed, std::uint64_t step,
                   std::size_t grain = kDefaultGrain);

/// Re-localization: appends n particles uniform over free space (as initialize_uniform draws
/// them, from Philox keyed by seed, step and RngPurpose::kRelocalize) that carry 1 - kept of the
/// belief, while the particles already there keep `kept` of it in their present proportions.
/// log-weights must be normalized; they are again afterwards. n = 0 or a space without a free
/// cell adds nothing.
void append_uniform(ParticleStore& store, std::size_t n, double kept, const FreeSpace& space,
                    std::uint64_t seed, std::uint64_t step, std::size_t grain = kDefaultGrain);

/// Sets every particle to mean + L n with L L^T = covariance (Cholesky, Eigen) and n standard
/// normal from Philox (seed, step 0, RngPurpose::kInitial); theta wrapped; uniform weights.
/// covariance over (x m, y m, theta rad) must be symmetric positive semi-definite (a zero
/// variance is allowed); throws ConfigError otherwise.
void initialize_gaussian(ParticleStore& store, std::size_t n, const Pose2& mean,
                         const Eigen::Matrix3d& covariance, std::uint64_t seed,
                         std::size_t grain = kDefaultGrain);

/// Global localization: n particles uniform over free space with uniform headings and uniform
/// weights. Throws ConfigError when the space has no free cell.
void initialize_uniform(ParticleStore& store, std::size_t n, const FreeSpace& space,
                        std::uint64_t seed, std::size_t grain = kDefaultGrain);

}  // namespace mote
