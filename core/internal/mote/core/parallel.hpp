#pragma once
/// \file
/// mote's small parallel vocabulary on TBB (internal, not installed). Every kernel goes through
/// these three calls, so determinism is argued once, here:
///  - chunk boundaries are multiples of kVectorWidth and of the grain, never of the thread count,
///    so a vectorized loop body treats every particle the same way (design.md section 3);
///  - reductions compute one partial per block of a fixed block grid in parallel and combine the
///    partials in block order on the calling thread, so the result depends on n and the block
///    size only;
///  - scans are over integers, so any association gives the exact serial result.
/// All three are tbb::parallel_for over blocks: partial results live in plain per-block slots
/// rather than inside TBB's reduction and scan nodes, which ThreadSanitizer could not follow
/// (see ForkJoin).
/// The calls run in the caller's task arena (see mote::Executor); a one-thread arena runs the
/// same code serially.

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

// ThreadSanitizer cannot see the fork/join synchronization of the system libtbb, which is not
// instrumented: every write a worker made inside a parallel call and the caller read after it
// would be reported. ForkJoin states the happens-before edges TBB guarantees: the caller's
// writes before a call happen before every task, and every task happens before the call
// returns. Tasks stay unordered among themselves, so a race between two chunks is still
// reported. Without TSan the annotations compile to nothing.
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
  void joined() { acquire(&join_); }       // in the caller, after the algorithm

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
/// whole number of vectors), in parallel, then join(join(join(identity, p_0), p_1), ...) in
/// block order on the calling thread.
template <class T, class Partial, class Join>
[[nodiscard]] T reduce(std::size_t n, std::size_t block, T identity, const Partial& partial,
                       const Join& join) {
  if (n == 0) return identity;
  const std::size_t step = aligned_grain(block);
  if (n <= step) return join(identity, partial(std::size_t{0}, n));
  std::vector<T> partials((n + step - 1) / step, identity);
  for_each_chunk(n, step, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; b += step) {
      partials[b / step] = partial(b, std::min(end, b + step));
    }
  });
  T result = std::move(identity);
  for (const T& p : partials) result = join(result, p);
  return result;
}

/// Exclusive prefix sum of integers whose values a block at a time writes: fill(begin, end, out)
/// sets out[i] for i in [begin, end) (a vector kernel, say). out[i] = sum of the values before i;
/// returns the total. Integer addition is associative, so the result equals the serial one
/// exactly: block sums in parallel (out holds the values meanwhile), a serial scan of the block
/// sums, then each block turns its values into prefix sums in parallel.
template <class Int, class Fill>
Int exclusive_scan_filled(std::size_t n, std::size_t grain, Int* out, const Fill& fill) {
  static_assert(std::is_integral_v<Int>, "scans are integer-only to stay exact");
  if (n == 0) return Int{0};
  const std::size_t step = aligned_grain(grain);
  std::vector<Int> block_start((n + step - 1) / step);
  for_each_chunk(n, step, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; b += step) {
      // Two loops: the values alone vectorize; fused with the running sum they stayed scalar.
      const std::size_t block_end = std::min(end, b + step);
      fill(b, block_end, out);
      Int sum{0};
      for (std::size_t i = b; i < block_end; ++i) sum += out[i];
      block_start[b / step] = sum;
    }
  });
  Int total{0};
  for (Int& b : block_start) {
    const Int sum = b;
    b = total;
    total += sum;
  }
  for_each_chunk(n, step, [&](std::size_t begin, std::size_t end) {
    Int running = block_start[begin / step];  // blocks inside one chunk are contiguous
    for (std::size_t i = begin; i < end; ++i) {
      const Int v = out[i];
      out[i] = running;
      running += v;
    }
  });
  return total;
}

/// Exclusive prefix sum of integers: out[i] = sum of value(j) for j < i; returns the total.
/// value(i) is called once per element (exclusive_scan_filled says how).
template <class Int, class Value>
Int exclusive_scan(std::size_t n, std::size_t grain, Int* out, const Value& value) {
  return exclusive_scan_filled<Int>(n, grain, out,
                                    [&](std::size_t begin, std::size_t end, Int* block) {
                                      for (std::size_t i = begin; i < end; ++i) {
                                        block[i] = static_cast<Int>(value(i));
                                      }
                                    });
}

}  // namespace mote::par
