#pragma once
// Histogram bins of poses and an open-addressing map from bin key to bin number
// (engine-internal). The clustering runs once per update over every particle, and a node-based
// std::unordered_map cost more there than motion and resampling together.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "mote/engine/estimate.hpp"

namespace mote::detail {

struct BinCoord {
  std::int64_t x, y, t;
};

// Maps poses to (x, y, theta) bins of a ClusterConfig and bins to 64-bit keys.
class BinIndex {
 public:
  explicit BinIndex(const ClusterConfig& c)
      : inv_x_(1.0 / c.bin_x),
        inv_y_(1.0 / c.bin_y),
        inv_t_(1.0 / c.bin_theta),
        nt_(c.connectivity == Connectivity::k8
                ? 1
                : static_cast<std::int64_t>(std::ceil(2.0 * std::numbers::pi / c.bin_theta))) {}

  // theta in (-pi, pi] (the store's invariant); other values are wrapped first.
  [[nodiscard]] BinCoord coord(double x, double y, double theta) const {
    if (!(theta > -std::numbers::pi && theta <= std::numbers::pi)) theta = wrap_angle(theta);
    const auto t = static_cast<std::int64_t>(std::floor((theta + std::numbers::pi) * inv_t_));
    return {static_cast<std::int64_t>(std::floor(x * inv_x_)),
            static_cast<std::int64_t>(std::floor(y * inv_y_)), nt_ == 1 ? 0 : t % nt_};
  }
  // 24 bits each for x and y (+-8M bins), 16 for theta.
  [[nodiscard]] static std::uint64_t key(const BinCoord& b) {
    constexpr std::uint64_t kMask = (std::uint64_t{1} << 24) - 1;
    return ((static_cast<std::uint64_t>(b.x) & kMask) << 40) |
           ((static_cast<std::uint64_t>(b.y) & kMask) << 16) | static_cast<std::uint64_t>(b.t);
  }
  [[nodiscard]] std::int64_t theta_bins() const { return nt_; }

 private:
  double inv_x_, inv_y_, inv_t_;
  std::int64_t nt_;
};

// Bin key -> bin number, numbers handed out in order of first insertion. Linear probing in a
// power-of-two table kept at most half full; memory is kept between clear() calls.
class BinMap {
 public:
  static constexpr std::uint32_t kAbsent = ~std::uint32_t{0};

  void clear() {
    if (size_ > 0) std::fill(slots_.begin(), slots_.end(), Slot{});
    size_ = 0;
  }
  [[nodiscard]] std::uint32_t size() const { return size_; }

  // The number of `key`, inserting it as the next number when new.
  std::uint32_t insert(std::uint64_t key) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    Slot& s = slots_[slot_of(key)];
    if (s.id == kAbsent) s = {key, size_++};
    return s.id;
  }
  [[nodiscard]] std::uint32_t find(std::uint64_t key) const {
    return slots_.empty() ? kAbsent : slots_[slot_of(key)].id;
  }

 private:
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t id = kAbsent;
  };
  // The slot holding `key`, or the empty slot where it would go.
  [[nodiscard]] std::size_t slot_of(std::uint64_t key) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = (key * 0x9E3779B97F4A7C15ULL) >> shift_ & mask;  // Fibonacci hashing
    while (slots_[i].id != kAbsent && slots_[i].key != key) i = (i + 1) & mask;
    return i;
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    const std::size_t capacity = std::max<std::size_t>(64, 2 * old.size());
    slots_.assign(capacity, Slot{});
    shift_ = 64 - std::countr_zero(capacity);
    for (const Slot& s : old) {
      if (s.id != kAbsent) slots_[slot_of(s.key)] = s;
    }
  }

  std::vector<Slot> slots_;
  std::uint32_t size_ = 0;
  int shift_ = 64;
};

}  // namespace mote::detail
