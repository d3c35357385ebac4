#pragma once
/// \file
/// A particle store for states that are not 2D poses: `dims` float columns plus the log-weight,
/// with the same layout promises as ParticleStore (64-byte aligned columns, padded to a multiple
/// of 16, double-buffered, integer scratch for resampling). The pose store's normalize, ESS,
/// resampling and KLD code runs on it unchanged (the bodies are shared, see resample_impl.hpp),
/// so a linear-Gaussian or a discrete model can be filtered by the same kernels as MCL and
/// checked against an exact filter (Kalman, histogram).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mote/engine/chunks.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/weights.hpp"

namespace mote {

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

/// Owner of `dims` state columns and a log-weight column, double-buffered. Like ParticleStore,
/// memory only grows; resizing within the capacity never allocates.
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

/// normalize() of weights.hpp on a StateStore's log-weights (the same code).
NormalizeResult normalize(const StateView& states, std::size_t grain = kDefaultGrain);
/// effective_sample_size() of weights.hpp on normalized log-weights (the same code).
[[nodiscard]] double effective_sample_size(const ConstStateView& states);

/// The resampling schemes of resample.hpp on a StateStore: every column is gathered by the
/// same ancestor index; results match the pose store's draw for draw (same weights, seed, step).
void resample_systematic(StateStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain = kDefaultGrain);
void resample_systematic_serial(StateStore& store, std::size_t n_out, std::uint64_t seed,
                                std::uint64_t step);
void resample_multinomial(StateStore& store, std::size_t n_out, std::uint64_t seed,
                          std::uint64_t step, std::size_t grain = kDefaultGrain);
void resample_stratified(StateStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain = kDefaultGrain);
void resample_residual(StateStore& store, std::size_t n_out, std::uint64_t seed,
                       std::uint64_t step);

/// KLD histogram over N unbounded dimensions: the bin of a particle is floor(value / size) per
/// column, and distinct bins are counted exactly by sorting the bin rows (O(N log N), serial
/// sort after a parallel binning pass). Buffers are reused between calls.
class StateKldBins {
 public:
  /// One positive bin size per state column; throws ConfigError otherwise.
  explicit StateKldBins(std::vector<double> bin_sizes);
  /// Number of distinct bins occupied by the particles (weights ignored). Deterministic.
  [[nodiscard]] std::size_t count(const ConstStateView& states, std::size_t grain = kDefaultGrain);

 private:
  std::vector<float> inv_sizes_;
  std::vector<std::int64_t> rows_;    // count x dims bin indices
  std::vector<std::uint32_t> order_;  // particle order sorted by bin row
};

/// k from the occupied bins, then n = kld_sample_count(k, config) (Fox 2003, eq. 13).
[[nodiscard]] std::size_t kld_sample_count(const ConstStateView& states, StateKldBins& bins,
                                           const KldConfig& config,
                                           std::size_t grain = kDefaultGrain);
/// KLD-sampling with one systematic pass, as resample_kld_systematic for poses. Returns n.
std::size_t resample_kld_systematic(StateStore& store, StateKldBins& bins, const KldConfig& config,
                                    std::uint64_t seed, std::uint64_t step,
                                    std::size_t grain = kDefaultGrain);

}  // namespace mote
