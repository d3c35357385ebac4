#pragma once
/// \file
/// The kernels on a StateStore (state_columns.hpp), for states that are not 2D poses: `dims`
/// float columns plus the log-weight, the same store ParticleStore is. The pose store's normalize,
/// ESS, resampling and KLD code runs on it unchanged (the bodies are shared, see
/// resample_impl.hpp), so a linear-Gaussian or a discrete model can be filtered by the same kernels
/// as MCL and checked against an exact filter (Kalman, histogram).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mote/engine/chunks.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/state_columns.hpp"
#include "mote/engine/weights.hpp"

namespace mote {

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
