#pragma once
/// \file
/// The instruction set of mote's dispatched kernels (design.md section 3, "Portability"). A
/// default build compiles the library for baseline x86-64 and compiles the few hot kernels
/// (likelihood-field weighting, the beam model's batched likelihood, motion sampling) once per
/// instruction set below; the variant is chosen once per process, on first use, from what the
/// CPU supports. Results are bit-identical for any thread count within one variant; two
/// variants may differ in the last bits (FMA contraction, vector widths).

#include <string>
#include <string_view>

namespace mote {

/// Kernel variants, from the baseline up.
enum class Isa {
  kGeneric,  ///< baseline x86-64 (SSE2), or whatever the compiler targets elsewhere
  kAvx2,     ///< AVX2 + FMA (Haswell, Zen and later)
  kAvx512,   ///< AVX-512 F/DQ/BW/VL + AVX2 + FMA (Skylake-SP, Ice Lake, Zen 4 and later)
};

/// "generic", "avx2" or "avx512".
[[nodiscard]] std::string_view isa_name(Isa isa) noexcept;

/// The best variant this CPU (and OS) supports among those compiled in.
[[nodiscard]] Isa best_supported_isa() noexcept;

/// The variant every dispatched kernel uses in this process: best_supported_isa(), lowered to
/// the environment variable MOTE_ISA (generic, avx2 or avx512) when that is set; a request
/// above what the CPU supports is clamped to best_supported_isa(). Fixed on the first call.
[[nodiscard]] Isa active_isa() noexcept;

/// One line for `mote --version` and report.json: the active variant and how the library was
/// compiled, e.g. "avx2 (dispatched; library compiled for baseline x86-64)".
[[nodiscard]] std::string isa_description();

}  // namespace mote
