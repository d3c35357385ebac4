// The fixed-point weights of resampling (resample_impl.hpp), compiled per instruction set: the
// float exp and the double-to-uint64 conversion are most of the resample phase, and baseline
// x86-64 has no vector form of the conversion.
#include <cstddef>
#include <cstdint>

#include "mote/core/isa_target.hpp"
#include "mote/engine/fast_math.hpp"
#include "resample_impl.hpp"

namespace mote::detail {
namespace {

MOTE_ALWAYS_INLINE void fixed_point_loop(const float* logw, double scale, std::uint64_t* out,
                                         std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    out[i] = static_cast<std::uint64_t>(static_cast<double>(fast_exp(logw[i])) * scale);
  }
}

MOTE_ISA_VARIANTS(fixed_point, fixed_point_loop,
                  (const float* logw, double scale, std::uint64_t* out, std::size_t begin,
                   std::size_t end),
                  (logw, scale, out, begin, end))

}  // namespace

void fixed_point_block(const float* logw, double scale, std::uint64_t* out, std::size_t begin,
                       std::size_t end) {
  static const auto kernel =
      pick_variant(&fixed_point_generic, &fixed_point_avx2, &fixed_point_avx512);
  kernel(logw, scale, out, begin, end);
}

}  // namespace mote::detail
