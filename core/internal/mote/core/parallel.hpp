#pragma once
/// \file
/// mote's small parallel vocabulary on TBB (internal, not installed). Every kernel goes through
/// these three calls, so determinism is argued once, here:
///  - chunk boundaries are multiples of kVectorWidth and of the grain, never of the thread count,
///    so a vectorized loop body treats every particle the same way (design.md section 3);
///  - reductions split a fixed block grid with tbb::parallel_deterministic_reduce and a
///    simple_partitioner, so the reduction tree depends on n and the block size only;
///  - scans are over integers, so any association gives the exact serial result.
/// The calls run in the caller's task arena (see mote::Executor); a one-thread arena runs the
/// same code serially.

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_reduce.h>
#include <oneapi/tbb/parallel_scan.h>
#include <oneapi/tbb/partitioner.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

// ThreadSanitizer cannot see the fork/join synchronization of the system libtbb, which is not
// instrumented: every write a worker made inside a parallel call and the caller read after it
// would be reported. ForkJoin states the happens-before edges TBB guarantees: the caller's
// writes before a call happen before every task, every task happens before the call returns
// and before any join of partial results. Tasks stay unordered among themselves, so a race
// between two chunks is still reported. Without TSan the annotations compile to nothing.
#if defined(__SANITIZE_THREAD__)
#define MOTE_TSAN_ANNOTATIONS 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define MOTE_TSAN_ANNOTATIONS 1
#endif
#endif

#ifdef MOTE_TSAN_ANNOTATIONS
extern "C" void __tsan_acquire(void* addr);  // NOLINT(bugprone-reserved-identifier)
extern "C" void __tsan_release(void* addr);  // NOLINT(bugprone-reserved-identifier)
#endif

namespace mote::par {

namespace detail {
class ForkJoin {
 public:
  ForkJoin() { release(&fork_); }          // in the caller, before the algorithm
  void task_begins() { acquire(&fork_); }  // in a task, before the body
  void task_ends() { release(&join_); }    // in a task, after the body
  void joined() { acquire(&join_); }       // after the algorithm, or before a join
  void join_ends() { release(&join_); }    // after a join of partial results

 private:
  static void acquire([[maybe_unused]] char* token) {
#ifdef MOTE_TSAN_ANNOTATIONS
    __tsan_acquire(token);
#endif
  }
  static void release([[maybe_unused]] char* token) {
#ifdef MOTE_TSAN_ANNOTATIONS
    __tsan_release(token);
#endif
  }
  // Only their addresses are used, as TSan sync objects; never written, so that reusing this
  // stack slot after the call is not itself a (false) race with a worker's annotation.
  char fork_;
  char join_;
};
}  // namespace detail

/// Columns are padded to this many elements; chunk boundaries are multiples of it.
inline constexpr std::size_t kVectorWidth = 16;

/// Default number of elements per task.
inline constexpr std::size_t kDefaultGrain = 4096;

/// Rounds n up to a multiple of kVectorWidth.
[[nodiscard]] constexpr std::size_t pad_to_vector(std::size_t n) noexcept {
  return (n + kVectorWidth - 1) / kVectorWidth * kVectorWidth;
}

/// The grain rounded up to a whole, non-zero number of vectors.
[[nodiscard]] constexpr std::size_t aligned_grain(std::size_t grain) noexcept {
  return pad_to_vector(std::max<std::size_t>(grain, 1));
}

/// Calls body(begin, end) over disjoint chunks covering [0, n); every begin is a multiple of the
/// aligned grain, so results never depend on which thread took which chunk.
template <class Body>
void for_each_chunk(std::size_t n, std::size_t grain, const Body& body) {
  if (n == 0) return;
  const std::size_t step = aligned_grain(grain);
  const std::size_t chunks = (n + step - 1) / step;
  if (chunks == 1) {
    body(std::size_t{0}, n);
    return;
  }
  detail::ForkJoin sync;
  tbb::parallel_for(
      /*range=*/tbb::blocked_range<std::size_t>(0, chunks, 1),
      /*body=*/
      [&](const tbb::blocked_range<std::size_t>& r) {
        sync.task_begins();
        body(r.begin() * step, std::min(n, r.end() * step));
        sync.task_ends();
      },
      /*partitioner=*/tbb::simple_partitioner());
  sync.joined();
}

/// Deterministic reduction: partial(begin, end) -> T over blocks of `block` elements (rounded to a
/// whole number of vectors), combined by join in a tree that depends only on n and block.
template <class T, class Partial, class Join>
[[nodiscard]] T reduce(std::size_t n, std::size_t block, T identity, const Partial& partial,
                       const Join& join) {
  if (n == 0) return identity;
  const std::size_t step = aligned_grain(block);
  const std::size_t blocks = (n + step - 1) / step;
  detail::ForkJoin sync;
  T result = tbb::parallel_deterministic_reduce(
      /*range=*/tbb::blocked_range<std::size_t>(0, blocks, 1),
      /*identity=*/identity,
      /*body=*/
      [&](const tbb::blocked_range<std::size_t>& r, T acc) {
        sync.task_begins();
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
          acc = join(acc, partial(b * step, std::min(n, (b + 1) * step)));
        }
        sync.task_ends();
        return acc;
      },
      /*join=*/
      [&](const T& a, const T& b) {
        sync.joined();
        T joined = join(a, b);
        sync.join_ends();
        return joined;
      },
      /*partitioner=*/tbb::simple_partitioner());
  sync.joined();
  return result;
}

/// Exclusive prefix sum of integers: out[i] = sum of value(j) for j < i; returns the total.
/// Integer addition is associative, so the parallel result equals the serial one exactly.
template <class Int, class Value>
Int exclusive_scan(std::size_t n, std::size_t grain, Int* out, const Value& value) {
  static_assert(std::is_integral_v<Int>, "scans are integer-only to stay exact");
  detail::ForkJoin sync;
  const Int total = tbb::parallel_scan(
      /*range=*/tbb::blocked_range<std::size_t>(0, n, aligned_grain(grain)),
      /*identity=*/Int{0},
      /*scan body=*/
      [&](const tbb::blocked_range<std::size_t>& r, Int running, bool is_final) {
        sync.task_begins();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          if (is_final) out[i] = running;
          running += static_cast<Int>(value(i));
        }
        sync.task_ends();
        return running;
      },
      /*join=*/[](Int left, Int right) { return left + right; });
  sync.joined();
  return total;
}

}  // namespace mote::par
