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
  std::int32_t x, y, t;
};

// Maps poses to (x, y, theta) bins of a ClusterConfig and bins to 64-bit keys. Float math,
// branch-free: the summarizer's loop over every particle vectorizes.
class BinIndex {
 public:
  explicit BinIndex(const ClusterConfig& c)
      : inv_x_(static_cast<float>(1.0 / c.bin_x)),
        inv_y_(static_cast<float>(1.0 / c.bin_y)),
        inv_t_(static_cast<float>(1.0 / c.bin_theta)),
        nt_(c.connectivity == Connectivity::k8
                ? 1
                : static_cast<std::int32_t>(std::ceil(2.0 * std::numbers::pi / c.bin_theta))) {}

  // Any theta is wrapped into [0, nt) bins; coordinates are clamped to +-8e6 bins (NaN to the
  // lower bound) so the casts are defined.
  [[nodiscard]] BinCoord coord(float x, float y, float theta) const {
    constexpr float kPi = std::numbers::pi_v<float>;
    const auto nt = static_cast<float>(nt_);
    float t = std::floor(bounded((theta + kPi) * inv_t_));
    t -= nt * std::floor(t / nt);
    return {static_cast<std::int32_t>(std::floor(bounded(x * inv_x_))),
            static_cast<std::int32_t>(std::floor(bounded(y * inv_y_))),
            static_cast<std::int32_t>(t)};
  }
  // 24 bits each for x and y (+-8M bins), 16 for theta.
  [[nodiscard]] static std::uint64_t key(const BinCoord& b) {
    constexpr std::uint32_t kMask = (std::uint32_t{1} << 24) - 1;
    return (std::uint64_t{static_cast<std::uint32_t>(b.x) & kMask} << 40) |
           (std::uint64_t{static_cast<std::uint32_t>(b.y) & kMask} << 16) |
           static_cast<std::uint32_t>(b.t);
  }
  [[nodiscard]] std::uint64_t key_of(float x, float y, float theta) const {
    return key(coord(x, y, theta));
  }
  [[nodiscard]] std::int32_t theta_bins() const { return nt_; }

 private:
  [[nodiscard]] static float bounded(float v) {
    constexpr float kLimit = 8.0e6F;
    return v > -kLimit ? (v < kLimit ? v : kLimit) : -kLimit;
  }

  float inv_x_, inv_y_, inv_t_;
  std::int32_t nt_;
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
