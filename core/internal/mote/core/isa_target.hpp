#pragma once
// Per-instruction-set kernel variants (internal to mote's libraries; mote/core/isa.hpp says what
// is promised).
//
// A dispatched kernel is written once as an always-inline body and compiled three times through
// wrappers carrying a GCC/clang target attribute and `flatten`: the body, and every inline
// helper it calls (fast_math.hpp, philox.hpp; flatten inlines them even where the inliner's
// budget would not), is inlined into each wrapper and vectorized for that wrapper's instruction
// set. Nothing is compiled with -mavx2 for a whole translation unit, so no inline function of a
// header (ours or the standard library's) is ever emitted out of line with AVX2 code that the
// linker could then pick for a generic caller.

#include "mote/core/isa.hpp"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define MOTE_ISA_DISPATCH 1
#define MOTE_TARGET_GENERIC __attribute__((flatten))
#define MOTE_TARGET_AVX2 __attribute__((target("avx2,fma"), flatten))
#define MOTE_TARGET_AVX512 \
  __attribute__((target("avx512f,avx512dq,avx512bw,avx512vl,avx2,fma"), flatten))
#else
#define MOTE_ISA_DISPATCH 0
#define MOTE_TARGET_GENERIC
#define MOTE_TARGET_AVX2
#define MOTE_TARGET_AVX512
#endif

#define MOTE_ALWAYS_INLINE inline __attribute__((always_inline))

// Defines name_generic, name_avx2 and name_avx512 with the parameter list params, each calling
// body args (an always-inline function) compiled for its instruction set.
#define MOTE_ISA_VARIANTS(name, body, params, args)             \
  MOTE_TARGET_GENERIC void name##_generic params { body args; } \
  MOTE_TARGET_AVX2 void name##_avx2 params { body args; }       \
  MOTE_TARGET_AVX512 void name##_avx512 params { body args; }

// The same for a body that returns a value of type type.
#define MOTE_ISA_VARIANTS_RETURNING(type, name, body, params, args)    \
  MOTE_TARGET_GENERIC type name##_generic params { return body args; } \
  MOTE_TARGET_AVX2 type name##_avx2 params { return body args; }       \
  MOTE_TARGET_AVX512 type name##_avx512 params { return body args; }

namespace mote::detail {

// The variant of a dispatched kernel for the active instruction set: one of three function
// pointers (generic, avx2, avx512), chosen once per call site from active_isa().
template <class Fn>
[[nodiscard]] Fn pick_variant(Fn generic, Fn avx2, Fn avx512) noexcept {
  switch (active_isa()) {
    case Isa::kAvx512:
      return avx512;
    case Isa::kAvx2:
      return avx2;
    case Isa::kGeneric:
      break;
  }
  return generic;
}

}  // namespace mote::detail
