// Clusters of connected occupied (x, y, theta) bins, found by a breadth-first search over the
// occupied bins (amcl builds the same clusters from its kd-tree leaves). Bins are numbered in
// order of their first particle, and searches start from bins in that order, so cluster
// numbering depends on the particle order only.

#include "cluster_labels.hpp"

namespace mote::detail {

std::vector<std::uint32_t> label_bins(const std::vector<BinCoord>& bins, const BinMap& id_of,
                                      std::int32_t nt) {
  constexpr std::uint32_t kUnlabeled = BinMap::kAbsent;
  std::vector<std::uint32_t> label(bins.size(), kUnlabeled);
  const std::int32_t dt_max = nt >= 3 ? 1 : 0;  // with 1 or 2 theta bins every pair touches
  std::vector<std::uint32_t> queue;  // FIFO of the breadth-first search: read position `head`
  queue.reserve(bins.size());
  std::uint32_t next = 0;
  for (std::uint32_t seed = 0; seed < bins.size(); ++seed) {
    if (label[seed] != kUnlabeled) continue;
    queue.assign(1, seed);
    label[seed] = next;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const BinCoord b = bins[queue[head]];
      for (std::int32_t dx = -1; dx <= 1; ++dx) {
        for (std::int32_t dy = -1; dy <= 1; ++dy) {
          for (std::int32_t dt = -dt_max; dt <= dt_max; ++dt) {
            const BinCoord n{b.x + dx, b.y + dy, ((b.t + dt) % nt + nt) % nt};  // theta wraps
            const std::uint32_t id = id_of.find(BinIndex::key(n));
            if (id == BinMap::kAbsent || label[id] != kUnlabeled) continue;
            label[id] = next;
            queue.push_back(id);
          }
        }
      }
    }
    ++next;
  }
  return label;
}

}  // namespace mote::detail
