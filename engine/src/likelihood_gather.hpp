#pragma once
// The likelihood-field inner loops (engine-internal): for a block of particles, each particle's
// pose in table cells, then for every beam endpoint the table value under the particle's
// projected endpoint, summed over the beams. Dispatched per instruction set (isa_target.hpp).

#include <cstddef>

#include "mote/engine/particles.hpp"
#include "mote/maps/likelihood_table.hpp"

namespace mote::detail {

// The most particles one call handles; sum must hold that many floats.
inline constexpr std::size_t kLikelihoodBlock = 256;

// Beam endpoints in the robot frame, m.
struct Endpoints {
  const float* x;
  const float* y;
  std::size_t count;
};

// sum[k] = sum over beams b of the table value at particle begin + k's endpoint b, for
// k < lanes (lanes <= kLikelihoodBlock, a multiple of the padding or running to the end of the
// padded columns). sum is 64-byte aligned. Every variant computes LikelihoodView::at_cell on
// col = col0 + c bx - s by, row = row0 + s bx + c by; the AVX2 and AVX-512 ones with fused
// multiply-adds and the hardware gather.
void likelihood_block_sums(const LikelihoodView& table, const ParticleView& particles,
                           std::size_t begin, std::size_t lanes, const Endpoints& endpoints,
                           float* sum);

}  // namespace mote::detail
