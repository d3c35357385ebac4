// KLD-sampling. Fox (2003) grows the sample while drawing it: after each draw from the weighted
// set, update k (the bins the draws so far occupy) and stop once n >= n(k) samples exist. A
// systematic draw has no order in which to stop, so the same rule runs on whole draws: draw
// n = min_particles, count the bins its ancestors occupy (known from the fixed-point prefix sum
// alone, before anything is gathered), and if n(k) > n draw again with n(k) teeth, until the
// draw is large enough for its own bins. Each round is deterministic, so the count is too.
// Counting the bins of the whole weighted set instead (its support) counts every bin holding a
// negligible weight, such as each scattered recovery particle, and grows the set where Fox's
// rule would not.

#include "mote/engine/kld.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/fast_math.hpp"
#include "mote/engine/resample.hpp"
#include "resample_impl.hpp"

namespace mote {

double standard_normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw ConfigError("standard_normal_quantile: p must be in (0, 1)");
  // Acklam's coefficients for the central and tail regions.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,
                                 -2.759285104469687e+02, 1.383577518672690e+02,
                                 -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02,
                                 -1.556989798598866e+02, 6.680131188771972e+01,
                                 -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01,
                                 -2.400758277161838e+00, -2.549732539343734e+00,
                                 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01,
                                 2.445134137142996e+00, 3.754408661907416e+00};
  constexpr double kLow = 0.02425;
  double x = 0.0;
  if (p < kLow || p > 1.0 - kLow) {
    const double q = std::sqrt(-2.0 * std::log(p < kLow ? p : 1.0 - p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
    if (p > 1.0 - kLow) x = -x;
  } else {
    const double q = p - 0.5;
    const double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  // One Halley step against the exact CDF 0.5 erfc(-x / sqrt 2).
  const double e = 0.5 * std::erfc(-x / std::numbers::sqrt2) - p;
  const double u = e * std::sqrt(2.0 * std::numbers::pi) * std::exp(0.5 * x * x);
  return x - u / (1.0 + 0.5 * x * u);
}

double chi_square_quantile(double dof, double z) {
  const double a = 2.0 / (9.0 * dof);
  return dof * std::pow(1.0 - a + std::sqrt(a) * z, 3.0);
}

std::size_t kld_sample_count(std::size_t k, const KldConfig& config) {
  if (k <= 1) return config.min_particles;
  const double z = config.use_z ? config.z : standard_normal_quantile(1.0 - config.delta);
  const double n =
      std::ceil(chi_square_quantile(static_cast<double>(k - 1), z) / (2.0 * config.epsilon));
  const double bounded = std::clamp(n, static_cast<double>(config.min_particles),
                                    static_cast<double>(config.max_particles));
  return static_cast<std::size_t>(bounded);
}

namespace {

// At most 2^32 bins, a 512 MB bitset: smaller bins over the region are a configuration error,
// not an allocation to attempt.
constexpr double kMaxBins = 4294967296.0;

// Validates the sizes and the region before the member initializers divide by the sizes and
// convert bin counts to integers (both undefined for a zero, NaN or infinite size).
const Bounds2& checked(const Bounds2& region, double bin_x, double bin_y, double bin_theta) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const bool region_ok = std::isfinite(region.min_x) && std::isfinite(region.min_y) &&
                         std::isfinite(region.max_x) && std::isfinite(region.max_y) &&
                         region.max_x >= region.min_x && region.max_y >= region.min_y;
  if (!positive(bin_x) || !positive(bin_y) || !positive(bin_theta) || !region_ok) {
    throw ConfigError(
        "KldBins: bin sizes must be positive and finite, the region finite and non-empty");
  }
  const double bins = (std::ceil((region.max_x - region.min_x) / bin_x) + 1.0) *
                      (std::ceil((region.max_y - region.min_y) / bin_y) + 1.0) *
                      std::ceil(2.0 * std::numbers::pi / bin_theta);
  if (!(bins <= kMaxBins)) {
    throw ConfigError("KldBins: " + std::to_string(bins) +
                      " bins over the region, more than 2^32: the bin sizes are too small");
  }
  return region;
}

}  // namespace

KldBins::KldBins(const Bounds2& region, double bin_x, double bin_y, double bin_theta)
    : region_(checked(region, bin_x, bin_y, bin_theta)),
      inv_x_(static_cast<float>(1.0 / bin_x)),
      inv_y_(static_cast<float>(1.0 / bin_y)),
      inv_t_(static_cast<float>(1.0 / bin_theta)),
      nx_(static_cast<std::size_t>(std::ceil((region.max_x - region.min_x) / bin_x)) + 1),
      ny_(static_cast<std::size_t>(std::ceil((region.max_y - region.min_y) / bin_y)) + 1),
      nt_(static_cast<std::size_t>(std::ceil(2.0 * std::numbers::pi / bin_theta))) {
  words_.resize((nx_ * ny_ * nt_ + 63) / 64);
}

std::uint64_t KldBins::bin_of(float x, float y, float theta) const noexcept {
  constexpr float kPi = 3.14159265F;
  // floor(v) clamped to [0, n - 1], NaN to 0 (std::clamp would pass NaN through to the
  // conversion, undefined, and in practice an index far past the bitset). The min guards
  // against n - 1 rounding up in float.
  const auto clamp_bin = [](float v, std::size_t n) {
    const float f = std::floor(v);
    const float hi = static_cast<float>(n - 1);
    const float bounded = f >= 0.0F ? (f < hi ? f : hi) : 0.0F;
    return std::min(static_cast<std::uint64_t>(bounded), std::uint64_t{n - 1});
  };
  const std::uint64_t i = clamp_bin((x - static_cast<float>(region_.min_x)) * inv_x_, nx_);
  const std::uint64_t j = clamp_bin((y - static_cast<float>(region_.min_y)) * inv_y_, ny_);
  // Theta in (-pi, pi] shifted to [0, 2 pi): bins wrap, the last one may be narrower.
  const std::uint64_t t = clamp_bin((fast_wrap_angle(theta) + kPi) * inv_t_, nt_);
  return (t * ny_ + j) * nx_ + i;
}

std::size_t KldBins::count(const ConstParticleView& p, std::size_t grain) {
  return count_where(
      p, [](std::size_t) { return true; }, grain);
}

template <class Keep>
std::size_t KldBins::count_where(const ConstParticleView& p, const Keep& keep, std::size_t grain) {
  // The bitset is all zero between calls. A bin counts once, for the one particle whose
  // fetch_or turns its bit on: the sum does not depend on the order the chunks run in, and the
  // work is proportional to the particles, not to the map (a 490 m map has 24 M bins, which a
  // clear and a count over every word paid on each of an update's draw rounds).
  std::uint64_t* words = words_.data();
  const std::size_t k = par::reduce(
      p.size(), grain, std::size_t{0},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        std::size_t fresh = 0;
        for (std::size_t i = begin; i < end; ++i) {
          if (!keep(i)) continue;
          const std::uint64_t bin = bin_of(p.x[i], p.y[i], p.theta[i]);
          std::atomic_ref<std::uint64_t> word(words[bin >> 6]);
          const std::uint64_t bit = std::uint64_t{1} << (bin & 63);
          if ((word.load(std::memory_order_relaxed) & bit) == 0 &&
              (word.fetch_or(bit, std::memory_order_relaxed) & bit) == 0) {
            ++fresh;
          }
        }
        return fresh;
      },
      /*join=*/[](std::size_t a, std::size_t b) { return a + b; });
  clear(p, grain);
  return k;
}

void KldBins::clear(const ConstParticleView& p, std::size_t grain) {
  if (words_.size() <= p.size()) {
    std::fill(words_.begin(), words_.end(), 0);
    return;
  }
  // Fewer particles than words: zero the words the particles can have set, every one of them
  // whether kept or not (a word zeroed twice is still zero).
  std::uint64_t* words = words_.data();
  par::for_each_chunk(p.size(), grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint64_t bin = bin_of(p.x[i], p.y[i], p.theta[i]);
      std::atomic_ref<std::uint64_t>(words[bin >> 6]).store(0, std::memory_order_relaxed);
    }
  });
}

std::size_t kld_sample_count(const ConstParticleView& particles, KldBins& bins,
                             const KldConfig& config, std::size_t grain) {
  // A fixed count needs no bins: the formula's n would be clamped to it anyway.
  if (config.min_particles == config.max_particles) return config.max_particles;
  return kld_sample_count(bins.count(particles, grain), config);
}

namespace {

// The pose store's log-weights and prefix-sum scratch, as detail::fixed_point_weights reads them.
struct WeightColumn {
  ParticleStore& store;
  [[nodiscard]] std::size_t size() const { return store.size(); }
  [[nodiscard]] const float* log_weights() const { return store.view().logw; }
  [[nodiscard]] std::uint64_t* scratch(int which) const { return store.scratch(which); }
};

// Draw rounds at most: each round that grows multiplies n by about n(k) / n, which is 10 and
// more for a spread-out set (k near n, n(k) near k / (2 epsilon)), so a handful reach
// max_particles from min_particles.
constexpr int kMaxDrawRounds = 16;

}  // namespace

std::size_t KldBins::count_drawn(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                                 std::uint64_t step, std::size_t grain) {
  WeightColumn column{store};
  const detail::FixedWeights fw = detail::fixed_point_weights(column, n_out, grain);
  if (fw.total == 0) return count(std::as_const(store).view(), grain);
  const std::uint64_t u = detail::comb_offset(seed, step);
  // Particle i is drawn when a comb tooth falls in [C_i, C_i+1), as in detail::systematic.
  return count_where(
      std::as_const(store).view(),
      [&](std::size_t i) {
        return detail::first_tooth(fw.c[i + 1], u, fw, n_out) >
               detail::first_tooth(fw.c[i], u, fw, n_out);
      },
      grain);
}

std::size_t kld_draw_count(ParticleStore& store, KldBins& bins, const KldConfig& config,
                           std::uint64_t seed, std::uint64_t step, std::size_t grain) {
  if (config.min_particles == config.max_particles) return config.max_particles;
  std::size_t n = config.min_particles;
  for (int round = 0; round < kMaxDrawRounds && n < config.max_particles; ++round) {
    const std::size_t wanted =
        kld_sample_count(bins.count_drawn(store, n, seed, step, grain), config);
    if (wanted <= n) break;
    n = wanted;
  }
  return n;
}

std::size_t resample_kld_systematic(ParticleStore& store, KldBins& bins, const KldConfig& config,
                                    std::uint64_t seed, std::uint64_t step, std::size_t grain) {
  const std::size_t n = kld_draw_count(store, bins, config, seed, step, grain);
  resample_systematic(store, n, seed, step, grain);
  return n;
}

}  // namespace mote
