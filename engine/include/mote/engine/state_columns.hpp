#pragma once
/// \file
/// The column store under every particle set (design.md section 2): `dims` float columns plus
/// the log-weight, 64-byte aligned, padded to a multiple of 16 and double-buffered so that
/// resampling gathers into the spare buffer without allocating; two integer scratch columns for
/// the resampling prefix sums. ParticleStore (particles.hpp) is its three-column pose form,
/// StateStore (state_store.hpp) adds the kernels for any number of columns.

#include <cstddef>
#include <cstdint>
#include <memory>

namespace mote {

/// Alignment of every particle column, bytes (one cache line, one AVX-512 register).
inline constexpr std::size_t kParticleAlignment = 64;

/// Columns are padded to a multiple of this many particles (mote::par::kVectorWidth).
inline constexpr std::size_t kParticlePadding = 16;

/// Rounds n up to a whole number of kParticlePadding.
[[nodiscard]] constexpr std::size_t pad_particles(std::size_t n) noexcept {
  return (n + kParticlePadding - 1) / kParticlePadding * kParticlePadding;
}

/// Mutable view of one buffer: column c of particle i is column(c)[i].
struct StateView {
  float* data = nullptr;   ///< column c starts at data + c * stride
  float* logw = nullptr;   ///< log-weights
  std::size_t stride = 0;  ///< floats between columns (the store's capacity)
  std::size_t dims = 0;    ///< number of state columns
  std::size_t count = 0;   ///< number of particles

  [[nodiscard]] float* column(std::size_t c) const noexcept { return data + c * stride; }
  [[nodiscard]] std::size_t size() const noexcept { return count; }
  [[nodiscard]] std::size_t padded_size() const noexcept { return pad_particles(count); }
};

/// Read-only view of one buffer (same layout as StateView).
struct ConstStateView {
  const float* data = nullptr;
  const float* logw = nullptr;
  std::size_t stride = 0;
  std::size_t dims = 0;
  std::size_t count = 0;

  ConstStateView() = default;
  /// Every mutable view converts to a read-only one.
  ConstStateView(const StateView& v) noexcept  // NOLINT(google-explicit-constructor)
      : data(v.data), logw(v.logw), stride(v.stride), dims(v.dims), count(v.count) {}

  [[nodiscard]] const float* column(std::size_t c) const noexcept { return data + c * stride; }
  [[nodiscard]] std::size_t size() const noexcept { return count; }
};

/// Owner of `dims` state columns and a log-weight column, double-buffered. Memory only grows
/// (in capacity); resizing within the capacity never allocates, so a filter whose particle
/// count goes up and down (KLD) allocates only on new maxima. ParticleStore is this store with
/// the three columns x, y, theta.
class StateStore {
 public:
  /// A store of n particles with `dims` >= 1 columns, all zero, uniform weights. Throws
  /// ConfigError when dims is 0.
  explicit StateStore(std::size_t dims, std::size_t n = 0);

  [[nodiscard]] std::size_t dims() const noexcept { return dims_; }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }

  /// Makes room for n particles in both buffers; allocates only when n exceeds capacity().
  void reserve(std::size_t n);
  /// Sets the particle count; new particles and padding lanes are 0 with log-weight -log(n).
  void resize(std::size_t n);

  [[nodiscard]] StateView view() noexcept { return view_of(current_, size_); }
  [[nodiscard]] ConstStateView view() const noexcept { return view_of(current_, size_); }
  /// The spare buffer sized for n <= capacity() particles (a resampling target).
  [[nodiscard]] StateView spare(std::size_t n) noexcept { return view_of(1 - current_, n); }
  /// Makes the spare buffer current with n particles.
  void swap_buffers(std::size_t n) noexcept;
  /// Integer scratch column (which = 0 or 1) of capacity() + 1 entries.
  [[nodiscard]] std::uint64_t* scratch(int which) noexcept { return scratch_[which].get(); }
  /// Sets every log-weight (and padding lane) to -log(size()).
  void set_uniform_weights() noexcept;

 private:
  struct AlignedFree {
    void operator()(float* p) const noexcept;
  };
  [[nodiscard]] StateView view_of(int buffer, std::size_t n) const noexcept;
  void fill_tail(std::size_t from) noexcept;

  std::size_t dims_;
  std::unique_ptr<float[], AlignedFree> buffers_[2];  // dims_ + 1 columns of capacity_ floats
  std::unique_ptr<std::uint64_t[]> scratch_[2];
  std::size_t capacity_ = 0;
  std::size_t size_ = 0;
  int current_ = 0;
};

}  // namespace mote
