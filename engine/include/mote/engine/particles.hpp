#pragma once
/// \file
/// The particle set as structure-of-arrays columns (design.md section 2): x, y, theta and the
/// log-weight, float32, 64-byte aligned, padded to a multiple of 16 and double-buffered so that
/// resampling gathers into the spare buffer without allocating.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "mote/core/pose.hpp"

namespace mote {

/// Alignment of every particle column, bytes (one cache line, one AVX-512 register).
inline constexpr std::size_t kParticleAlignment = 64;

/// Columns are padded to a multiple of this many particles (mote::par::kVectorWidth).
inline constexpr std::size_t kParticlePadding = 16;

/// Rounds n up to a whole number of kParticlePadding.
[[nodiscard]] constexpr std::size_t pad_particles(std::size_t n) noexcept {
  return (n + kParticlePadding - 1) / kParticlePadding * kParticlePadding;
}

/// Mutable spans over one particle buffer. Index i < size() is a particle; indices in
/// [size(), padded_size()) are padding lanes that kernels may compute on and must never report.
struct ParticleView {
  float* x = nullptr;      ///< m, map frame
  float* y = nullptr;      ///< m, map frame
  float* theta = nullptr;  ///< rad, wrapped to (-pi, pi]
  float* logw = nullptr;   ///< natural log of the (possibly unnormalized) weight
  std::size_t count = 0;   ///< number of particles

  [[nodiscard]] std::size_t size() const noexcept { return count; }
  [[nodiscard]] std::size_t padded_size() const noexcept { return pad_particles(count); }
  [[nodiscard]] std::span<float> xs() const noexcept { return {x, count}; }
  [[nodiscard]] std::span<float> ys() const noexcept { return {y, count}; }
  [[nodiscard]] std::span<float> thetas() const noexcept { return {theta, count}; }
  [[nodiscard]] std::span<float> log_weights() const noexcept { return {logw, count}; }

  /// Particle i as a double-precision pose.
  [[nodiscard]] Pose2 pose(std::size_t i) const noexcept { return {x[i], y[i], theta[i]}; }
  /// Stores pose p (rounded to float) at index i.
  void set_pose(std::size_t i, const Pose2& p) const noexcept {
    x[i] = static_cast<float>(p.x);
    y[i] = static_cast<float>(p.y);
    theta[i] = static_cast<float>(wrap_angle(p.theta));
  }
};

/// Read-only spans over one particle buffer (same layout as ParticleView).
struct ConstParticleView {
  const float* x = nullptr;      ///< m
  const float* y = nullptr;      ///< m
  const float* theta = nullptr;  ///< rad
  const float* logw = nullptr;   ///< log-weight
  std::size_t count = 0;         ///< number of particles

  ConstParticleView() = default;
  ConstParticleView(const float* px, const float* py, const float* pt, const float* pw,
                    std::size_t n) noexcept
      : x(px), y(py), theta(pt), logw(pw), count(n) {}
  /// Every mutable view converts to a read-only one.
  ConstParticleView(const ParticleView& v) noexcept  // NOLINT(google-explicit-constructor)
      : x(v.x), y(v.y), theta(v.theta), logw(v.logw), count(v.count) {}

  [[nodiscard]] std::size_t size() const noexcept { return count; }
  [[nodiscard]] std::size_t padded_size() const noexcept { return pad_particles(count); }
  [[nodiscard]] Pose2 pose(std::size_t i) const noexcept { return {x[i], y[i], theta[i]}; }
};

/// Owner of the particle columns: two buffers (current and spare) plus integer scratch space for
/// resampling. Memory only grows (in capacity); resizing within the capacity never allocates, so
/// a filter whose particle count goes up and down (KLD) allocates only on new maxima.
class ParticleStore {
 public:
  /// An empty store; reserve() or resize() before use.
  ParticleStore() = default;
  /// A store of n particles at the origin with uniform weights.
  explicit ParticleStore(std::size_t n);

  /// Number of particles in the current buffer.
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  /// Particles the store holds without allocating (a multiple of kParticlePadding).
  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }

  /// Makes room for n particles in both buffers; allocates only when n exceeds capacity().
  void reserve(std::size_t n);
  /// Sets the particle count of the current buffer. New particles and padding lanes are at the
  /// origin with log-weight -log(n); existing particles keep their values.
  void resize(std::size_t n);

  /// The current particles.
  [[nodiscard]] ParticleView view() noexcept { return view_of(current_, size_); }
  [[nodiscard]] ConstParticleView view() const noexcept { return const_view_of(current_, size_); }

  /// The spare buffer sized for n particles (n <= capacity() after reserve(n)), e.g. as a
  /// resampling target. Its contents are unspecified until written.
  [[nodiscard]] ParticleView spare(std::size_t n) noexcept { return view_of(1 - current_, n); }
  /// Makes the spare buffer current with n particles (what a gather into spare(n) wrote).
  void swap_buffers(std::size_t n) noexcept;

  /// Two integer scratch columns of capacity() + 1 entries each (resampling prefix sums).
  [[nodiscard]] std::uint64_t* scratch(int which) noexcept { return scratch_[which].get(); }

  /// Sets every log-weight (and padding lane) to -log(size()).
  void set_uniform_weights() noexcept;

 private:
  struct AlignedFree {
    void operator()(float* p) const noexcept;
  };
  using Column = std::unique_ptr<float[], AlignedFree>;

  [[nodiscard]] ParticleView view_of(int buffer, std::size_t n) const noexcept;
  [[nodiscard]] ConstParticleView const_view_of(int buffer, std::size_t n) const noexcept;
  void fill_tail(std::size_t from) noexcept;

  Column buffers_[2];  // each holds 4 columns of capacity_ floats: x, y, theta, logw
  std::unique_ptr<std::uint64_t[]> scratch_[2];
  std::size_t capacity_ = 0;
  std::size_t size_ = 0;
  int current_ = 0;
};

}  // namespace mote
