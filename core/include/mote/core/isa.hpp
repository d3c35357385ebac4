#pragma once
/// \file
/// The instruction set of mote's dispatched kernels (design.md section 3, "Portability"). A
/// default build compiles the libraries for baseline x86-64 and compiles the few hot kernels
/// (likelihood-field weighting, the beam model's batched likelihood, motion sampling, the
/// confirmed range table's claims) once per instruction set below; the variant is chosen once
/// per process, on first use, from what the CPU supports. Results are bit-identical for any
/// thread count within one variant; two variants may differ in the last bits (FMA contraction,
/// vector widths). Header-only, so that every library of mote (ray casting below the engine)
/// dispatches on the one choice.

#include <cstdlib>
#include <iostream>
#include <string_view>

namespace mote {

/// Kernel variants, from the baseline up.
enum class Isa {
  kGeneric,  ///< baseline x86-64 (SSE2), or whatever the compiler targets elsewhere
  kAvx2,     ///< AVX2 + FMA (Haswell, Zen and later)
  kAvx512,   ///< AVX-512 F/DQ/BW/VL + AVX2 + FMA (Skylake-SP, Ice Lake, Zen 4 and later)
};

/// "generic", "avx2" or "avx512".
[[nodiscard]] inline std::string_view isa_name(Isa isa) noexcept {
  switch (isa) {
    case Isa::kAvx2:
      return "avx2";
    case Isa::kAvx512:
      return "avx512";
    case Isa::kGeneric:
      break;
  }
  return "generic";
}

namespace detail {

/// What this CPU runs among the compiled variants.
[[nodiscard]] inline Isa detect_isa() noexcept {
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f") &&
                      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
                      __builtin_cpu_supports("avx512vl");
  return avx512 ? Isa::kAvx512 : (avx2 ? Isa::kAvx2 : Isa::kGeneric);
#else
  return Isa::kGeneric;
#endif
}

/// MOTE_ISA as a variant; an unknown value is reported once and ignored.
[[nodiscard]] inline Isa requested_isa(Isa best) {
  const char* value = std::getenv("MOTE_ISA");
  if (value == nullptr || *value == '\0') return best;
  const std::string_view v(value);
  for (const Isa isa : {Isa::kGeneric, Isa::kAvx2, Isa::kAvx512}) {
    if (v == isa_name(isa)) return isa;
  }
  std::cerr << "mote: MOTE_ISA=" << v << " is not generic, avx2 or avx512; using " << isa_name(best)
            << '\n';
  return best;
}

/// The request clamped to what the CPU runs.
[[nodiscard]] inline Isa choose_isa() noexcept {
  const Isa best = detect_isa();
  try {
    const Isa want = requested_isa(best);
    return static_cast<int>(want) < static_cast<int>(best) ? want : best;
  } catch (...) {  // std::cerr failing: keep the detected variant
    return best;
  }
}

}  // namespace detail

/// The best variant this CPU (and OS) supports among those compiled in.
[[nodiscard]] inline Isa best_supported_isa() noexcept {
  static const Isa best = detail::detect_isa();
  return best;
}

/// The variant every dispatched kernel uses in this process: best_supported_isa(), lowered to
/// the environment variable MOTE_ISA (generic, avx2 or avx512) when that is set; a request
/// above what the CPU supports is clamped to best_supported_isa(). Fixed on the first call.
[[nodiscard]] inline Isa active_isa() noexcept {
  static const Isa active = detail::choose_isa();
  return active;
}

}  // namespace mote
