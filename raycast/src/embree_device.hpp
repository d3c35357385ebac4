#pragma once
/// \file
/// Internal: the process's one Embree device and the floating-point mode Embree wants.

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

namespace mote::detail {

/// The Embree device shared by every RayCaster in the process, created on first use with an
/// error callback that throws mote::Error. Its config names no thread count: "threads=" would
/// cap the whole process's TBB pool (design.md section 3, "Threads").
[[nodiscard]] RTCDevice embree_device();

/// Throws mote::Error if Embree recorded an error on this thread since the last check (for
/// calls whose failure the callback could not turn into an exception).
void check_embree(const char* what);

/// Sets flush-to-zero and denormals-are-zero in this thread's MXCSR while alive, then restores
/// the previous mode: denormal arithmetic slows Embree's traversal (design.md section 4).
class FlushDenormals {
 public:
  FlushDenormals() noexcept : saved_(_mm_getcsr()) {
    _mm_setcsr(saved_ | _MM_FLUSH_ZERO_ON | _MM_DENORMALS_ZERO_ON);
  }
  ~FlushDenormals() { _mm_setcsr(saved_); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned int saved_;
};

}  // namespace mote::detail
