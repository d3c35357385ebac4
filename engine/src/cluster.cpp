// Clusters of connected occupied (x, y, theta) bins, found by a breadth-first search over the
// occupied bins (amcl builds the same clusters from its kd-tree leaves). Bins are numbered in
// order of their first particle, and searches start from bins in that order, so cluster
// numbering depends on the particle order only.

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "moments.hpp"
#include "mote/engine/estimate.hpp"

namespace mote {
namespace {

struct BinCoord {
  std::int64_t x, y, t;
};

class BinIndex {
 public:
  BinIndex(const ClusterConfig& c)
      : config_(c),
        nt_(c.connectivity == Connectivity::k8
                ? 1
                : static_cast<std::int64_t>(std::ceil(2.0 * std::numbers::pi / c.bin_theta))) {}

  [[nodiscard]] BinCoord coord(double x, double y, double theta) const {
    const auto t = static_cast<std::int64_t>(
        std::floor((wrap_angle(theta) + std::numbers::pi) / config_.bin_theta));
    return {static_cast<std::int64_t>(std::floor(x / config_.bin_x)),
            static_cast<std::int64_t>(std::floor(y / config_.bin_y)), nt_ == 1 ? 0 : t % nt_};
  }
  // 24 bits each for x and y (+-8M bins), 16 for theta.
  [[nodiscard]] static std::uint64_t key(const BinCoord& b) {
    constexpr std::uint64_t kMask = (std::uint64_t{1} << 24) - 1;
    return ((static_cast<std::uint64_t>(b.x) & kMask) << 40) |
           ((static_cast<std::uint64_t>(b.y) & kMask) << 16) | static_cast<std::uint64_t>(b.t);
  }
  [[nodiscard]] std::int64_t theta_bins() const { return nt_; }

 private:
  ClusterConfig config_;
  std::int64_t nt_;
};

// Labels connected bins; returns the cluster of each bin (bins numbered by first appearance).
std::vector<int> label_bins(const std::vector<BinCoord>& bins,
                            const std::unordered_map<std::uint64_t, int>& id_of, std::int64_t nt) {
  std::vector<int> label(bins.size(), -1);
  const std::int64_t dt_max = nt >= 3 ? 1 : 0;  // with 1 or 2 theta bins every pair touches
  std::vector<std::size_t> queue;  // FIFO of the breadth-first search: read position `head`
  queue.reserve(bins.size());
  int next = 0;
  for (std::size_t seed = 0; seed < bins.size(); ++seed) {
    if (label[seed] >= 0) continue;
    queue.assign(1, seed);
    label[seed] = next;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const BinCoord b = bins[queue[head]];
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          for (std::int64_t dt = -dt_max; dt <= dt_max; ++dt) {
            const BinCoord n{b.x + dx, b.y + dy, ((b.t + dt) % nt + nt) % nt};  // theta wraps
            const auto it = id_of.find(BinIndex::key(n));
            if (it == id_of.end() || label[static_cast<std::size_t>(it->second)] >= 0) continue;
            label[static_cast<std::size_t>(it->second)] = next;
            queue.push_back(static_cast<std::size_t>(it->second));
          }
        }
      }
    }
    ++next;
  }
  return label;
}

}  // namespace

std::vector<PoseEstimate> cluster(const ConstParticleView& p, const ClusterConfig& config) {
  const BinIndex index(config);
  std::unordered_map<std::uint64_t, int> id_of;
  std::vector<BinCoord> bins;
  std::vector<int> bin_of(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const BinCoord b = index.coord(p.x[i], p.y[i], p.theta[i]);
    const auto [it, fresh] = id_of.try_emplace(BinIndex::key(b), static_cast<int>(bins.size()));
    if (fresh) bins.push_back(b);
    bin_of[i] = it->second;
  }
  const std::vector<int> label = label_bins(bins, id_of, index.theta_bins());
  int clusters = 0;
  for (const int l : label) clusters = std::max(clusters, l + 1);

  float max_logw = -std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) max_logw = std::max(max_logw, p.logw[i]);
  if (!std::isfinite(max_logw)) return {};
  const auto weight = [&](std::size_t i) {
    const float v = p.logw[i];
    return v == v ? std::exp(static_cast<double>(v - max_logw)) : 0.0;
  };
  const auto cluster_of = [&](std::size_t i) {
    return static_cast<std::size_t>(label[static_cast<std::size_t>(bin_of[i])]);
  };

  std::vector<detail::FirstMoments> first(static_cast<std::size_t>(clusters));
  double total = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    first[cluster_of(i)].add(weight(i), p.x[i], p.y[i], p.theta[i]);
    total += weight(i);
  }
  std::vector<PoseEstimate> out(first.size());
  std::vector<detail::SecondMoments> second(first.size());
  for (std::size_t c = 0; c < first.size(); ++c) out[c].mean = first[c].mean();
  for (std::size_t i = 0; i < p.size(); ++i) {
    second[cluster_of(i)].add(weight(i), out[cluster_of(i)].mean, p.x[i], p.y[i], p.theta[i]);
  }
  for (std::size_t c = 0; c < first.size(); ++c) {
    out[c].covariance =
        first[c].s[0] > 0 ? second[c].covariance(first[c].s[0]) : Eigen::Matrix3d::Zero().eval();
    out[c].weight = first[c].s[0] / total;
    out[c].count = first[c].count;
  }
  return out;
}

}  // namespace mote
