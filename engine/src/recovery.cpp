#include "mote/engine/recovery.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/philox.hpp"
#include "mote/engine/weights.hpp"

namespace mote {
namespace {

// log(exp(a) + exp(b)) without overflow or underflow; -inf when both are -inf.
double log_add_exp(double a, double b) {
  const double hi = std::max(a, b);
  if (hi == -std::numeric_limits<double>::infinity()) return hi;
  return hi + std::log1p(std::exp(std::min(a, b) - hi));
}

// One exponential-smoothing step of a log-average: log((1 - alpha) exp(avg) + alpha exp(x)).
double smooth(double log_avg, double log_x, double alpha) {
  if (alpha <= 0.0) return log_avg;
  if (alpha >= 1.0) return log_x;
  return log_add_exp(std::log1p(-alpha) + log_avg, std::log(alpha) + log_x);
}

// A pose uniform over free space for particle i: the cell index uses 32 random bits scaled to
// the cell count (bias below count / 2^32), the point and heading use the remaining words.
Pose2 free_pose(const FreeSpace& space, const RngStream& rng, std::uint32_t i) {
  const PhiloxCounter b = rng.block(i);
  const std::size_t cells = space.free_cell_count();
  const auto k = static_cast<std::size_t>((static_cast<std::uint64_t>(b[0]) * cells) >> 32);
  const Point2 p = space.free_point(k, bits_to_unit(b[1]), bits_to_unit(b[2]));
  return {p.x, p.y, (2.0 * bits_to_unit(b[3]) - 1.0) * std::numbers::pi};
}

}  // namespace

void AugmentedMcl::update(double log_mean_likelihood) noexcept {
  if (!started_) {
    log_slow_ = log_fast_ = log_mean_likelihood;
    started_ = std::isfinite(log_mean_likelihood);
    return;
  }
  log_slow_ = smooth(log_slow_, log_mean_likelihood, config_.alpha_slow);
  log_fast_ = smooth(log_fast_, log_mean_likelihood, config_.alpha_fast);
}

double AugmentedMcl::injection_probability() const noexcept {
  if (!started_ || !enabled()) return 0.0;
  if (log_slow_ == -std::numeric_limits<double>::infinity()) return 1.0;
  return std::max(0.0, 1.0 - std::exp(log_fast_ - log_slow_));
}

std::size_t inject_random_particles(const ParticleView& p, double probability,
                                    const FreeSpace& space, std::uint64_t seed, std::uint64_t step,
                                    std::size_t grain) {
  if (probability <= 0.0 || space.free_cell_count() == 0) return 0;
  const RngStream decide{seed, step, RngPurpose::kInjection};
  const RngStream where{seed, step, RngPurpose::kFreePose};
  return par::reduce(
      p.size(), grain, std::size_t{0},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        std::size_t replaced = 0;
        for (std::size_t i = begin; i < end; ++i) {
          const auto idx = static_cast<std::uint32_t>(i);
          if (decide.uniform_double(idx) >= probability) continue;
          p.set_pose(i, free_pose(space, where, idx));
          ++replaced;
        }
        return replaced;
      },
      /*join=*/[](std::size_t a, std::size_t b) { return a + b; });
}

std::size_t inject_into_weighted(const ParticleView& p, double probability, const FreeSpace& space,
                                 std::uint64_t seed, std::uint64_t step, std::size_t grain) {
  const std::size_t n = p.size();
  if (probability <= 0.0 || n == 0 || space.free_cell_count() == 0) return 0;
  // At most the mean weight, to float rounding: a freshly resampled set (every log-weight
  // -log N, as set_uniform_weights writes it) is eligible as a whole, as in the book.
  const float mean_logw = -std::log(static_cast<float>(n));
  const float eligible_below = mean_logw + 1e-6F * std::abs(mean_logw);
  const std::size_t below = par::reduce(
      n, grain, std::size_t{0},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        std::size_t k = 0;
        for (std::size_t i = begin; i < end; ++i) k += (p.logw[i] <= eligible_below) ? 1 : 0;
        return k;
      },
      /*join=*/[](std::size_t a, std::size_t b) { return a + b; });
  if (below == 0) return 0;
  const double replace =
      std::min(1.0, probability * static_cast<double>(n) / static_cast<double>(below));
  const RngStream decide{seed, step, RngPurpose::kInjection};
  const RngStream where{seed, step, RngPurpose::kFreePose};
  const std::size_t replaced = par::reduce(
      n, grain, std::size_t{0},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        std::size_t k = 0;
        for (std::size_t i = begin; i < end; ++i) {
          const auto idx = static_cast<std::uint32_t>(i);
          if (!(p.logw[i] <= eligible_below) || decide.uniform_double(idx) >= replace) continue;
          p.set_pose(i, free_pose(space, where, idx));
          p.logw[i] = mean_logw;
          ++k;
        }
        return k;
      },
      /*join=*/[](std::size_t a, std::size_t b) { return a + b; });
  (void)normalize(p, grain);
  return replaced;
}

namespace {

// Appends n particles drawn by pose(i) with the weights append_uniform() gives them.
template <class PoseOf>
void append_weighted(ParticleStore& store, std::size_t n, double kept, std::size_t grain,
                     const PoseOf& pose) {
  const std::size_t old = store.size();
  store.resize(old + n);
  const ParticleView p = store.view();
  const auto kept_log = static_cast<float>(std::log(kept));
  const auto fresh_log = static_cast<float>(std::log((1.0 - kept) / static_cast<double>(n)));
  par::for_each_chunk(old + n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (i < old) {
        p.logw[i] += kept_log;
        continue;
      }
      p.set_pose(i, pose(static_cast<std::uint32_t>(i - old)));
      p.logw[i] = fresh_log;
    }
  });
  (void)normalize(p, grain);
}

}  // namespace

void append_around(ParticleStore& store, std::size_t n, double kept, const Pose2& center,
                   double radius, std::uint64_t seed, std::uint64_t step, std::size_t grain) {
  if (n == 0 || !is_finite(center) || !(radius >= 0.0)) return;
  const RngStream rng{seed, step, RngPurpose::kLocalSearch};
  append_weighted(store, n, kept, grain, [&](std::uint32_t i) {
    const std::array<float, 4> z = rng.normal4(i);
    const double heading = (2.0 * bits_to_unit(rng.block(i, 1)[0]) - 1.0) * std::numbers::pi;
    return Pose2{center.x + 0.5 * radius * z[0], center.y + 0.5 * radius * z[1], heading};
  });
}

void append_uniform(ParticleStore& store, std::size_t n, double kept, const FreeSpace& space,
                    std::uint64_t seed, std::uint64_t step, std::size_t grain) {
  if (n == 0 || space.free_cell_count() == 0) return;
  const RngStream rng{seed, step, RngPurpose::kRelocalize};
  append_weighted(store, n, kept, grain, [&](std::uint32_t i) { return free_pose(space, rng, i); });
}

void initialize_gaussian(ParticleStore& store, std::size_t n, const Pose2& mean,
                         const Eigen::Matrix3d& covariance, std::uint64_t seed, std::size_t grain) {
  // LDLT with pivoting accepts semi-definite matrices (zero variances); L sqrt(D) is then a
  // square root of P^T covariance P, and the permutation is undone on the sample.
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(covariance);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      !covariance.isApprox(covariance.transpose()) || !covariance.allFinite()) {
    throw ConfigError("initialize_gaussian: covariance must be symmetric positive semi-definite");
  }
  const Eigen::Matrix3d root = ldlt.transpositionsP().transpose() *
                               Eigen::Matrix3d(ldlt.matrixL()) *
                               ldlt.vectorD().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  store.resize(n);
  const ParticleView p = store.view();
  const RngStream rng{seed, 0, RngPurpose::kInitial};
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::array<float, 4> z = rng.normal4(static_cast<std::uint32_t>(i));
      const Eigen::Vector3d d = root * Eigen::Vector3d(z[0], z[1], z[2]);
      p.set_pose(i, {mean.x + d.x(), mean.y + d.y(), mean.theta + d.z()});
    }
  });
  store.set_uniform_weights();
}

void initialize_uniform(ParticleStore& store, std::size_t n, const FreeSpace& space,
                        std::uint64_t seed, std::size_t grain) {
  if (space.free_cell_count() == 0) {
    throw ConfigError("initialize_uniform: the map has no free cell to place particles in");
  }
  store.resize(n);
  const ParticleView p = store.view();
  const RngStream rng{seed, 0, RngPurpose::kFreePose};
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      p.set_pose(i, free_pose(space, rng, static_cast<std::uint32_t>(i)));
    }
  });
  store.set_uniform_weights();
}

}  // namespace mote
