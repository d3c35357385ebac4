#pragma once
/// \file
/// Transparent huge pages for the map-sized arrays written once at start-up (internal, not
/// installed). Why: every 4 KB page an array touches first is a page fault, and in a virtual
/// machine a fault is slow: on the Intel map tiled 12 x 9 (67 M cells) the faults of the image,
/// the grid, the likelihood table and the signed field were a third of the start-up's CPU
/// samples, and advising those arrays for 2 MB pages took 512 times fewer faults (start to the
/// first update 2.1 -> 1.3 s; BENCHMARKS.md, "Large maps"); the range table's 190 MB on Intel's
/// map had been 11 % of its build's samples. Advice only: where the system has no
/// transparent huge pages (or "never"), the pages stay ordinary and nothing else changes.

#include <cstddef>
#include <cstdint>
#include <memory>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mote::huge_pages {

/// The huge page size the advice is for.
inline constexpr std::size_t kPageBytes = std::size_t{2} << 20U;

/// Advises the whole 2 MB pages inside [p, p + bytes) for transparent huge pages (none inside an
/// array below 2 MB). Call it before the first write: pages already touched stay 4 KB.
inline void advise(void* p, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + kPageBytes - 1) / kPageBytes * kPageBytes;
  const std::uintptr_t last = (begin + bytes) / kPageBytes * kPageBytes;
  // NOLINTNEXTLINE(performance-no-int-to-ptr): madvise takes the address as a pointer
  if (last > first) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

/// n uninitialized values, advised for huge pages before anything writes them.
template <class T>
std::unique_ptr<T[]> uninitialized(std::size_t n) {
  auto values = std::make_unique_for_overwrite<T[]>(n);
  advise(values.get(), n * sizeof(T));
  return values;
}

/// Reserves n elements of a vector (or string) and advises its storage before the caller
/// resizes or fills it. Storage that malloc reuses from its heap may be touched already; a new
/// map-sized block comes from mmap untouched.
template <class Container>
void reserve(Container& c, std::size_t n) {
  c.reserve(n);
  advise(c.data(), c.capacity() * sizeof(*c.data()));
}

}  // namespace mote::huge_pages
