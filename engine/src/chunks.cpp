#include "mote/engine/chunks.hpp"

#include "mote/core/parallel.hpp"

namespace mote {

void for_each_particle_chunk(std::size_t n, std::size_t grain, ChunkBody body) {
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) { body(begin, end); });
}

}  // namespace mote
