#pragma once
/// \file
/// Resampling: draw a new, equally weighted particle set from the normalized weights, gathering
/// into the store's spare buffer (no allocation once the store's capacity is reached).
///
/// Every scheme works on the same fixed-point weights: q_i = floor(w_i * n_out * 2^32), so q_i
/// is particle i's expected number of copies in 32.32 fixed point, and C = exclusive prefix sum
/// of q (an integer scan, hence identical in parallel and serial). Systematic resampling (the
/// low-variance sampler, Thrun table 4.4) places the n_out comb teeth at j * 2^32 + U for one
/// uniform U in [0, 2^32); particle i gets the teeth falling in [C_i, C_i + q_i), which is
/// floor(q_i / 2^32) or ceil(q_i / 2^32) of them. Teeth past the total (flooring loses < N / 2^32
/// of a copy) go to the last particle with positive weight.

#include <cstddef>
#include <cstdint>

#include "mote/engine/chunks.hpp"
#include "mote/engine/particles.hpp"

namespace mote {

/// Systematic resampling of the store's current, normalized particles into n_out particles,
/// in parallel: an integer prefix sum, then each input particle writes its own copies. Equal,
/// bit for bit, to resample_systematic_serial for any thread count and grain. Randomness: one
/// uniform keyed by (seed, step, RngPurpose::kResample). Afterwards the store holds n_out
/// particles with log-weights -log(n_out).
void resample_systematic(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain = kDefaultGrain);

/// The plain serial low-variance sampler (one pointer walking the comb; Thrun table 4.4) on the
/// same fixed-point weights: the reference resample_systematic is tested against.
void resample_systematic_serial(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                                std::uint64_t step);

/// Multinomial resampling (n_out independent draws, each a binary search of the prefix sums).
void resample_multinomial(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                          std::uint64_t step, std::size_t grain = kDefaultGrain);

/// Stratified resampling: one independent uniform inside each of the n_out strata.
void resample_stratified(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain = kDefaultGrain);

/// Residual resampling (serial): floor(n_out w_i) copies of each particle, then the remaining
/// copies by multinomial draws on the fractional parts.
void resample_residual(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                       std::uint64_t step);

}  // namespace mote
