#pragma once
/// \file
/// Internal: the process's one Embree device and the floating-point mode Embree wants.

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

namespace mote::detail {

/// The Embree device shared by every RayCaster in the process, created on first use with an
/// error callback that records the error for this thread (it never throws: it runs inside
/// Embree's C API). Its config names no thread count: "threads=" would cap the whole
/// process's TBB pool (design.md section 3, "Threads").
[[nodiscard]] RTCDevice embree_device();

/// Throws mote::Error ("Embree: <what>: <error name>: <Embree's message>") if Embree reported
/// an error on this thread since the last check, and clears it. Call it after Embree calls
/// that can fail, once they have returned.
void check_embree(const char* what);

/// As check_embree, from the callback's record alone (no Embree call: cheap enough for the
/// ray-casting loops).
void check_embree_thread(const char* what);

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
