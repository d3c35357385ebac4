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
#include "mote/engine/state_columns.hpp"

namespace mote {

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

/// Owner of the particle columns: the StateStore with the three columns x, y, theta (two
/// buffers, current and spare, plus integer scratch space for resampling).
class ParticleStore {
 public:
  /// An empty store; reserve() or resize() before use.
  ParticleStore() : columns_(3) {}
  /// A store of n particles at the origin with uniform weights.
  explicit ParticleStore(std::size_t n) : columns_(3, n) {}

  /// Number of particles in the current buffer.
  [[nodiscard]] std::size_t size() const noexcept { return columns_.size(); }
  /// Particles the store holds without allocating (a multiple of kParticlePadding).
  [[nodiscard]] std::size_t capacity() const noexcept { return columns_.capacity(); }

  /// Makes room for n particles in both buffers; allocates only when n exceeds capacity().
  void reserve(std::size_t n) { columns_.reserve(n); }
  /// Sets the particle count of the current buffer. New particles and padding lanes are at the
  /// origin with log-weight -log(n); existing particles keep their values.
  void resize(std::size_t n) { columns_.resize(n); }

  /// The current particles.
  [[nodiscard]] ParticleView view() noexcept { return poses(columns_.view()); }
  [[nodiscard]] ConstParticleView view() const noexcept { return poses(columns_.view()); }

  /// The spare buffer sized for n particles (n <= capacity() after reserve(n)), e.g. as a
  /// resampling target. Its contents are unspecified until written.
  [[nodiscard]] ParticleView spare(std::size_t n) noexcept { return poses(columns_.spare(n)); }
  /// Makes the spare buffer current with n particles (what a gather into spare(n) wrote).
  void swap_buffers(std::size_t n) noexcept { columns_.swap_buffers(n); }

  /// Two integer scratch columns of capacity() + 1 entries each (resampling prefix sums).
  [[nodiscard]] std::uint64_t* scratch(int which) noexcept { return columns_.scratch(which); }

  /// Sets every log-weight (and padding lane) to -log(size()).
  void set_uniform_weights() noexcept { columns_.set_uniform_weights(); }

 private:
  [[nodiscard]] static ParticleView poses(const StateView& v) noexcept {
    return {v.column(0), v.column(1), v.column(2), v.logw, v.count};
  }
  [[nodiscard]] static ConstParticleView poses(const ConstStateView& v) noexcept {
    return {v.column(0), v.column(1), v.column(2), v.logw, v.count};
  }

  StateStore columns_;
};

}  // namespace mote
