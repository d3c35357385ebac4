// PoseSummarizer: the whole-set estimate and the clusters in five passes over the particles.
//  1. max log-weight (parallel reduction);
//  2. weights exp(logw - max), bin keys and the whole-set first moments (parallel, fixed blocks);
//  3. bin numbers in order of first particle: each block of pass 2 numbers its own keys (one
//     flat-map lookup per change of key: resampled copies sit next to each other, so
//     consecutive particles mostly share a bin); a serial merge then numbers each block's
//     distinct keys in block order, which is the order of first particle;
//  4. cluster first moments (skipped for a single cluster: they are the whole-set moments);
//  5. second moments about the whole-set and cluster means (parallel, fixed blocks).
// Sums run over a fixed block grid, so every result is bit-identical for any thread count.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "cluster_labels.hpp"
#include "moments.hpp"
#include "mote/core/isa_target.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/estimate.hpp"
#include "mote/engine/fast_math.hpp"

namespace mote {
namespace {

using detail::FirstMoments;
using detail::SecondMoments;

// Sums run over blocks of this many particles, whatever the grain and the thread count.
constexpr std::size_t kSumBlock = 2048;

// Up to this many clusters, per-cluster sums run in parallel (one vector of sums per block);
// beyond it serially, to keep the per-block vectors small.
constexpr std::size_t kParallelClusterLimit = 64;

float max_log_weight(const ConstParticleView& p) {
  constexpr float kNegInf = -std::numeric_limits<float>::infinity();
  return par::reduce(
      p.size(), kSumBlock, kNegInf,
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        float m = kNegInf;
        for (std::size_t i = begin; i < end; ++i) m = std::max(m, p.logw[i]);
        return m;
      },
      /*join=*/[](float a, float b) { return std::max(a, b); });
}

// Weight relative to the largest, so an unnormalized set does not overflow; NaN weighs 0
// (fast_exp(-inf) is exactly 0). A select on the argument, not a branch: the loop vectorizes.
MOTE_ALWAYS_INLINE float relative_weight(float logw, float max_logw) {
  return fast_exp(logw == logw ? logw - max_logw : -std::numeric_limits<float>::infinity());
}

// v where keep, else +0.0, through a bit mask: a ?: on doubles keeps GCC 12 from vectorizing
// the moment loops.
MOTE_ALWAYS_INLINE double masked(double v, bool keep) {
  const std::uint64_t mask = keep ? ~std::uint64_t{0} : std::uint64_t{0};
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) & mask);
}

// Per-block sums in kLanes independent accumulators (lane j takes particles begin + j,
// begin + j + kLanes, ...), added up in lane order at the end: a fixed order, so the same for any
// thread count, and one the compiler can vectorize (a single running sum cannot be reordered).
constexpr std::size_t kLanes = 16;

template <std::size_t kSums, class Terms>
MOTE_ALWAYS_INLINE std::array<double, kSums> lane_sums(std::size_t count, const Terms& terms) {
  double acc[kSums][kLanes] = {};
  std::size_t k = 0;
  for (; k + kLanes <= count; k += kLanes) {
    for (std::size_t j = 0; j < kLanes; ++j) terms(k + j, acc, j);
  }
  for (; k < count; ++k) terms(k, acc, k % kLanes);
  std::array<double, kSums> total{};
  for (std::size_t q = 0; q < kSums; ++q) {
    for (std::size_t j = 0; j < kLanes; ++j) total[q] += acc[q][j];
  }
  return total;
}

// First moments of particles [begin, end) (end - begin <= kSumBlock) with weights w.
MOTE_ALWAYS_INLINE FirstMoments first_moments(const ConstParticleView& p, const float* w,
                                              std::size_t begin, std::size_t end) {
  alignas(64) float cos_t[kSumBlock];
  alignas(64) float sin_t[kSumBlock];
  const std::size_t count = end - begin;
  for (std::size_t k = 0; k < count; ++k) {
    const SinCos sc = fast_sin_cos(p.theta[begin + k]);
    cos_t[k] = sc.cos;
    sin_t[k] = sc.sin;
  }
  const float* x = p.x + begin;
  const float* y = p.y + begin;
  const float* wb = w + begin;
  FirstMoments m;
  // A particle without weight adds nothing, whatever its pose: 0 * NaN would be NaN (a
  // non-finite pose carries weight 0 after the sensor update). Selects, so the loop vectorizes.
  m.s = lane_sums<5>(count, [&](std::size_t k, double(&acc)[5][kLanes], std::size_t j) {
    const double wk = wb[k];
    const bool weighed = wk > 0.0;
    acc[0][j] += wk;
    acc[1][j] += masked(wk * x[k], weighed);
    acc[2][j] += masked(wk * y[k], weighed);
    acc[3][j] += masked(wk * cos_t[k], weighed);
    acc[4][j] += masked(wk * sin_t[k], weighed);
  });
  m.count = count;
  if (count > 0) m.first = p.pose(begin);
  return m;
}

// Second moments about `mean` of particles [begin, end) with weights w.
MOTE_ALWAYS_INLINE SecondMoments second_moments(const ConstParticleView& p, const float* w,
                                                const Pose2& mean, std::size_t begin,
                                                std::size_t end) {
  const float* x = p.x + begin;
  const float* y = p.y + begin;
  const float* theta = p.theta + begin;
  const float* wb = w + begin;
  SecondMoments m;
  m.s = lane_sums<6>(end - begin, [&](std::size_t k, double(&acc)[6][kLanes], std::size_t j) {
    const double wk = wb[k];
    const bool weighed = wk > 0.0;  // as in first_moments: no NaN from an unweighted pose
    const double dx = masked(x[k] - mean.x, weighed);
    const double dy = masked(y[k] - mean.y, weighed);
    const double dt = masked(detail::heading_residual(theta[k], mean.theta), weighed);
    acc[0][j] += wk * dx * dx;
    acc[1][j] += wk * dx * dy;
    acc[2][j] += wk * dx * dt;
    acc[3][j] += wk * dy * dy;
    acc[4][j] += wk * dy * dt;
    acc[5][j] += wk * dt * dt;
  });
  return m;
}

// Pass 2's vector work for the block [begin, end): the weights, the bin keys when index is set,
// and the first moments. Compiled per instruction set (isa_target.hpp).
MOTE_ALWAYS_INLINE FirstMoments weigh_block(const ConstParticleView& p, float max_logw,
                                            float* weight, const detail::BinIndex* index,
                                            std::uint64_t* keys, std::size_t begin,
                                            std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) weight[i] = relative_weight(p.logw[i], max_logw);
  if (index != nullptr) {
    // Locals: a store through the uint64 key column could alias the index's int64 fields.
    const detail::BinIndex bin_index = *index;
    const float* x = p.x;
    const float* y = p.y;
    const float* theta = p.theta;
    for (std::size_t i = begin; i < end; ++i) keys[i] = bin_index.key_of(x[i], y[i], theta[i]);
  }
  return first_moments(p, weight, begin, end);
}

MOTE_ISA_VARIANTS_RETURNING(FirstMoments, weigh_block, weigh_block,
                            (const ConstParticleView& p, float max_logw, float* weight,
                             const detail::BinIndex* index, std::uint64_t* keys, std::size_t begin,
                             std::size_t end),
                            (p, max_logw, weight, index, keys, begin, end))
MOTE_ISA_VARIANTS_RETURNING(SecondMoments, second_moments, second_moments,
                            (const ConstParticleView& p, const float* w, const Pose2& mean,
                             std::size_t begin, std::size_t end),
                            (p, w, mean, begin, end))

template <class Moments>
std::vector<Moments> add_vectors(std::vector<Moments> a, const std::vector<Moments>& b) {
  for (std::size_t c = 0; c < a.size(); ++c) a[c] = a[c] + b[c];
  return a;
}

}  // namespace

// The bins of one block of particles, numbered in the order of their first particle there.
struct BlockBins {
  detail::BinMap local;               // key -> number within the block
  std::vector<std::uint64_t> keys;    // block number -> key
  std::vector<std::uint32_t> first;   // block number -> its first particle
  std::vector<std::uint32_t> global;  // block number -> bin number over the whole set
};

struct PoseSummarizer::State {
  explicit State(const ClusterConfig& c) : index(c) {}

  detail::BinIndex index;
  std::vector<float> weight;             // exp(logw - max) per particle
  std::vector<std::uint64_t> key;        // bin key per particle
  std::vector<std::uint32_t> bin;        // bin number per particle (first within its block)
  std::vector<BlockBins> blocks;         // per block of kSumBlock particles
  detail::BinMap bins;                   // key -> bin number
  std::vector<detail::BinCoord> coords;  // bin number -> coordinates
  std::vector<std::uint32_t> label;      // bin number -> cluster
  ParticleSummary out;

  void summarize(const ConstParticleView& p, bool with_clusters);
  FirstMoments weigh_and_key(const ConstParticleView& p, float max_logw, bool with_keys);
  void number_block(std::size_t begin, std::size_t end);
  void number_bins(const ConstParticleView& p);
  void renumber_particles(std::size_t n);
  std::vector<FirstMoments> cluster_first(const ConstParticleView& p, std::size_t k) const;
  std::vector<SecondMoments> cluster_second(const ConstParticleView& p) const;
  SecondMoments overall_second(const ConstParticleView& p) const;
  std::uint32_t cluster_of(std::size_t i) const { return label[bin[i]]; }
};

FirstMoments PoseSummarizer::State::weigh_and_key(const ConstParticleView& p, float max_logw,
                                                  bool with_keys) {
  static const auto kernel =
      detail::pick_variant(&weigh_block_generic, &weigh_block_avx2, &weigh_block_avx512);
  return par::reduce(
      p.size(), kSumBlock, FirstMoments{},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        const FirstMoments m = kernel(p, max_logw, weight.data(), with_keys ? &index : nullptr,
                                      key.data(), begin, end);
        if (with_keys) number_block(begin, end);
        return m;
      },
      /*join=*/[](const FirstMoments& a, const FirstMoments& b) { return a + b; });
}

void PoseSummarizer::State::number_block(std::size_t begin, std::size_t end) {
  BlockBins& block = blocks[begin / kSumBlock];
  block.local.clear();
  block.keys.clear();
  block.first.clear();
  std::uint64_t last_key = 0;
  std::uint32_t last_bin = detail::BinMap::kAbsent;
  for (std::size_t i = begin; i < end; ++i) {
    if (key[i] != last_key || last_bin == detail::BinMap::kAbsent) {
      last_key = key[i];
      last_bin = block.local.insert(last_key);
      if (last_bin == block.keys.size()) {
        block.keys.push_back(last_key);
        block.first.push_back(static_cast<std::uint32_t>(i));
      }
    }
    bin[i] = last_bin;
  }
}

void PoseSummarizer::State::number_bins(const ConstParticleView& p) {
  bins.clear();
  coords.clear();
  for (std::size_t b = 0; b * kSumBlock < p.size(); ++b) {
    BlockBins& block = blocks[b];
    block.global.resize(block.keys.size());
    for (std::size_t q = 0; q < block.keys.size(); ++q) {
      block.global[q] = bins.insert(block.keys[q]);
      if (block.global[q] == coords.size()) {
        const std::uint32_t i = block.first[q];
        coords.push_back(index.coord(p.x[i], p.y[i], p.theta[i]));
      }
    }
  }
  label = detail::label_bins(coords, bins, index.theta_bins());
}

void PoseSummarizer::State::renumber_particles(std::size_t n) {
  par::for_each_chunk(n, kSumBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; b += kSumBlock) {
      const std::vector<std::uint32_t>& global = blocks[b / kSumBlock].global;
      for (std::size_t i = b; i < std::min(end, b + kSumBlock); ++i) bin[i] = global[bin[i]];
    }
  });
}

std::vector<FirstMoments> PoseSummarizer::State::cluster_first(const ConstParticleView& p,
                                                               std::size_t k) const {
  const auto partial = [&](std::size_t begin, std::size_t end) {
    std::vector<FirstMoments> m(k);
    for (std::size_t i = begin; i < end; ++i) {
      const SinCos sc = fast_sin_cos(p.theta[i]);
      m[cluster_of(i)].add(weight[i], p.x[i], p.y[i], sc.cos, sc.sin, p.theta[i]);
    }
    return m;
  };
  if (k > kParallelClusterLimit) return partial(0, p.size());
  return par::reduce(p.size(), kSumBlock, std::vector<FirstMoments>(k), partial,
                     add_vectors<FirstMoments>);
}

std::vector<SecondMoments> PoseSummarizer::State::cluster_second(const ConstParticleView& p) const {
  const std::size_t k = out.clusters.size();
  const auto partial = [&](std::size_t begin, std::size_t end) {
    std::vector<SecondMoments> m(k);
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t c = cluster_of(i);
      m[c].add(weight[i], out.clusters[c].mean, p.x[i], p.y[i], p.theta[i]);
    }
    return m;
  };
  if (k > kParallelClusterLimit) return partial(0, p.size());
  return par::reduce(p.size(), kSumBlock, std::vector<SecondMoments>(k), partial,
                     add_vectors<SecondMoments>);
}

SecondMoments PoseSummarizer::State::overall_second(const ConstParticleView& p) const {
  static const auto kernel =
      detail::pick_variant(&second_moments_generic, &second_moments_avx2, &second_moments_avx512);
  return par::reduce(
      p.size(), kSumBlock, SecondMoments{},
      /*partial=*/
      [&](std::size_t begin, std::size_t end) {
        return kernel(p, weight.data(), out.overall.mean, begin, end);
      },
      /*join=*/[](const SecondMoments& a, const SecondMoments& b) { return a + b; });
}

void PoseSummarizer::State::summarize(const ConstParticleView& p, bool with_clusters) {
  out = {};
  const float max_logw = max_log_weight(p);
  if (!std::isfinite(max_logw)) return;
  weight.resize(p.size());
  if (with_clusters) {
    key.resize(p.size());
    bin.resize(p.size());
    blocks.resize((p.size() + kSumBlock - 1) / kSumBlock);
  }
  const FirstMoments first = weigh_and_key(p, max_logw, with_clusters);
  out.overall.mean = first.mean();
  out.overall.covariance = overall_second(p).covariance(first.s[0]);
  out.overall.weight = 1.0;
  out.overall.count = p.size();
  if (!with_clusters) return;

  number_bins(p);
  const std::size_t k = label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + 1;
  if (k == 1) {  // one cluster: its sums are the whole set's
    out.clusters.assign(1, out.overall);
    return;
  }
  renumber_particles(p.size());
  const std::vector<FirstMoments> first_c = cluster_first(p, k);
  out.clusters.resize(k);
  for (std::size_t c = 0; c < k; ++c) out.clusters[c].mean = first_c[c].mean();
  const std::vector<SecondMoments> second_c = cluster_second(p);
  for (std::size_t c = 0; c < k; ++c) {
    PoseEstimate& e = out.clusters[c];
    e.covariance = first_c[c].s[0] > 0 ? second_c[c].covariance(first_c[c].s[0])
                                       : Eigen::Matrix3d::Zero().eval();
    e.weight = first_c[c].s[0] / first.s[0];
    e.count = first_c[c].count;
  }
}

PoseSummarizer::PoseSummarizer(const ClusterConfig& config)
    : state_(std::make_unique<State>(config)) {}
PoseSummarizer::~PoseSummarizer() = default;
PoseSummarizer::PoseSummarizer(PoseSummarizer&&) noexcept = default;
PoseSummarizer& PoseSummarizer::operator=(PoseSummarizer&&) noexcept = default;

const ParticleSummary& PoseSummarizer::operator()(const ConstParticleView& particles,
                                                  bool with_clusters) {
  state_->summarize(particles, with_clusters);
  return state_->out;
}

PoseEstimate estimate(const ConstParticleView& particles) {
  PoseSummarizer summarize;
  return summarize(particles, /*with_clusters=*/false).overall;
}

std::vector<PoseEstimate> cluster(const ConstParticleView& particles, const ClusterConfig& config) {
  PoseSummarizer summarize(config);
  return summarize(particles).clusters;
}

const PoseEstimate* best_cluster(const std::vector<PoseEstimate>& clusters) noexcept {
  const auto it = std::max_element(
      clusters.begin(), clusters.end(),
      [](const PoseEstimate& a, const PoseEstimate& b) { return a.weight < b.weight; });
  return it == clusters.end() ? nullptr : &*it;
}

}  // namespace mote
