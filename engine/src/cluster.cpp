// Clusters of connected occupied (x, y, theta) bins (amcl builds the same clusters from its
// kd-tree leaves). Bins are numbered in order of their first particle; a cluster's number is
// the rank of its lowest bin number, so cluster numbering depends on the particle order only.
//
// Connected components by union-find, parallel over the bins: every bin is united with each
// occupied neighbour, and a union always links the root with the higher number under the other,
// so each component's root ends up being its lowest bin whatever the order of the unions. The
// numbering is therefore the one a breadth-first search seeded in bin order gives, on any
// thread count.

#include <algorithm>
#include <atomic>
#include <memory>

#include "cluster_labels.hpp"
#include "mote/core/parallel.hpp"

namespace mote::detail {

namespace {

// Bins per parallel task: each bin looks up 13 of its 26 neighbours (unite_neighbours).
constexpr std::size_t kBinGrain = 1024;

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(std::make_unique<std::atomic<std::uint32_t>[]>(n)) {
    for (std::size_t i = 0; i < n; ++i) parent_[i].store(static_cast<std::uint32_t>(i));
  }

  // The root of x, halving the path on the way. Parents only ever point to lower bins and a
  // node's ancestors only gain new ones at the top, so storing an ancestor seen a moment ago is
  // always valid, whatever other threads do meanwhile.
  std::uint32_t root(std::uint32_t x) {
    std::uint32_t p = parent_[x].load(std::memory_order_acquire);
    while (p != x) {
      const std::uint32_t grandparent = parent_[p].load(std::memory_order_acquire);
      parent_[x].store(grandparent, std::memory_order_release);
      x = p;
      p = grandparent;
    }
    return x;
  }

  // Links the higher of the two roots under the lower; retries when another thread linked
  // that root first.
  void unite(std::uint32_t a, std::uint32_t b) {
    while (true) {
      std::uint32_t ra = root(a);
      std::uint32_t rb = root(b);
      if (ra == rb) return;
      if (ra < rb) std::swap(ra, rb);
      std::uint32_t expected = ra;
      if (parent_[ra].compare_exchange_strong(expected, rb, std::memory_order_acq_rel)) return;
    }
  }

 private:
  std::unique_ptr<std::atomic<std::uint32_t>[]> parent_;
};

// Above this many bins in the bounding box, neighbours are looked up in the hash map instead.
constexpr std::int64_t kMaxDenseBins = std::int64_t{1} << 22;  // 16 MB of bin numbers
// Above this many, without the bitmap that sends only the occupied ones there.
constexpr std::int64_t kMaxBitmapBins = std::int64_t{1} << 27;  // 16 MB of bits

// Bin number by coordinates. Spread particles occupy tens of thousands of bins, and a hash map
// that large misses L2 on most of the 26 lookups per bin; a dense array over the occupied bins'
// bounding box (plus one bin on each side in x and y) answers the same from a few cache lines.
// Boxes over kMaxDenseBins use the hash map behind a bitmap of the occupied bins: a global set
// on a 490 m map (500k particles, 24 M bins in the box, 2 % occupied) spent a third of its
// first update in the 27 hash lookups per bin, most of them for empty bins.
class BinLookup {
 public:
  BinLookup(const std::vector<BinCoord>& bins, const BinMap& id_of, std::int32_t nt)
      : id_of_(id_of), nt_(nt) {
    if (bins.empty()) return;
    std::int64_t x1 = bins[0].x;
    std::int64_t y1 = bins[0].y;
    x0_ = x1;
    y0_ = y1;
    for (const BinCoord& b : bins) {
      x0_ = std::min<std::int64_t>(x0_, b.x);
      x1 = std::max<std::int64_t>(x1, b.x);
      y0_ = std::min<std::int64_t>(y0_, b.y);
      y1 = std::max<std::int64_t>(y1, b.y);
    }
    width_ = x1 - x0_ + 3;
    const std::int64_t cells = width_ * (y1 - y0_ + 3) * nt;
    if (cells <= kMaxDenseBins) {
      dense_.assign(static_cast<std::size_t>(cells), BinMap::kAbsent);
      for (std::size_t i = 0; i < bins.size(); ++i) {
        dense_[index(bins[i])] = static_cast<std::uint32_t>(i);
      }
    } else if (cells <= kMaxBitmapBins) {
      occupied_.assign(static_cast<std::size_t>(cells + 63) / 64, 0);
      for (const BinCoord& b : bins)
        occupied_[index(b) / 64] |= std::uint64_t{1} << (index(b) % 64);
    }
  }

  // The number of bin n, or kAbsent; n lies within one bin of an occupied bin in x and y.
  [[nodiscard]] std::uint32_t find(const BinCoord& n) const {
    if (!dense_.empty()) return dense_[index(n)];
    if (!occupied_.empty() && (occupied_[index(n) / 64] >> (index(n) % 64) & 1U) == 0) {
      return BinMap::kAbsent;
    }
    return id_of_.find(BinIndex::key(n));
  }

 private:
  [[nodiscard]] std::size_t index(const BinCoord& c) const {
    const std::int64_t column = c.x - x0_ + 1;
    const std::int64_t row = c.y - y0_ + 1;
    return static_cast<std::size_t>((row * width_ + column) * nt_ + c.t);
  }

  const BinMap& id_of_;
  std::int64_t nt_;
  std::int64_t x0_ = 0;
  std::int64_t y0_ = 0;
  std::int64_t width_ = 0;
  std::vector<std::uint32_t> dense_;
  std::vector<std::uint64_t> occupied_;  // a bit per bin of the box, when dense_ is too large
};

void unite_neighbours(const std::vector<BinCoord>& bins, const BinLookup& lookup, std::int32_t nt,
                      std::uint32_t bin, UnionFind& sets) {
  const std::int32_t dt_max = nt >= 3 ? 1 : 0;  // with 1 or 2 theta bins every pair touches
  const BinCoord b = bins[bin];
  std::int32_t headings[3] = {b.t, b.t, b.t};
  for (std::int32_t dt = -dt_max; dt <= dt_max; ++dt) {
    headings[dt + 1] = ((b.t + dt) % nt + nt) % nt;  // theta wraps
  }
  // Each edge once: only the offsets after (0, 0, 0) in (dx, dy, dt) order, half of them; the
  // opposite offset is the other bin's. Unions commute (the file comment), so the order in
  // which the edges come does not matter.
  for (std::int32_t dx = 0; dx <= 1; ++dx) {
    for (std::int32_t dy = dx == 0 ? 0 : -1; dy <= 1; ++dy) {
      for (std::int32_t dt = dx == 0 && dy == 0 ? 1 : -dt_max; dt <= dt_max; ++dt) {
        const std::uint32_t id = lookup.find({b.x + dx, b.y + dy, headings[dt + 1]});
        if (id != BinMap::kAbsent) sets.unite(bin, id);
      }
    }
  }
}

}  // namespace

std::vector<std::uint32_t> label_bins(const std::vector<BinCoord>& bins, const BinMap& id_of,
                                      std::int32_t nt) {
  const std::size_t n = bins.size();
  UnionFind sets(n);
  const BinLookup lookup(bins, id_of, nt);
  par::for_each_chunk(n, kBinGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      unite_neighbours(bins, lookup, nt, static_cast<std::uint32_t>(i), sets);
    }
  });
  // Roots in bin order get 0, 1, 2, ...; every other bin's root is lower, so already numbered.
  std::vector<std::uint32_t> label(n);
  std::uint32_t next = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t r = sets.root(i);
    label[i] = r == i ? next++ : label[r];
  }
  return label;
}

}  // namespace mote::detail
