// Choosing the kernel variant once per process (isa.hpp).
#include "mote/engine/isa.hpp"

#include <cstdlib>
#include <iostream>

#include "isa_target.hpp"

namespace mote {
namespace {

Isa detect() noexcept {
#if MOTE_ISA_DISPATCH
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

// MOTE_ISA as a variant; an unknown value is reported once and ignored.
Isa requested(Isa best) {
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

Isa choose() noexcept {
  const Isa best = detect();
  try {
    const Isa want = requested(best);
    return static_cast<int>(want) < static_cast<int>(best) ? want : best;
  } catch (...) {  // std::cerr failing: keep the detected variant
    return best;
  }
}

}  // namespace

std::string_view isa_name(Isa isa) noexcept {
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

Isa best_supported_isa() noexcept {
  static const Isa best = detect();
  return best;
}

Isa active_isa() noexcept {
  static const Isa active = choose();
  return active;
}

std::string isa_description() {
#if defined(MOTE_NATIVE_BUILD)
  constexpr std::string_view kBuild = "library compiled with -march=native";
#else
  constexpr std::string_view kBuild = "library compiled for the compiler's default target";
#endif
  const std::string_view how = MOTE_ISA_DISPATCH ? "dispatched" : "no dispatch on this target";
  return std::string(isa_name(active_isa())) + " (" + std::string(how) + "; " +
         std::string(kBuild) + ")";
}

}  // namespace mote
