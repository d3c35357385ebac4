#include "huge_pages.hpp"

#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mote::detail {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20U;
}  // namespace

void FreeDeleter::operator()(void* p) const noexcept { std::free(p); }

void* allocate_huge_bytes(std::size_t bytes) {
  if (bytes < kHugePage) {  // a small map's table or columns: not worth a huge page
    void* small = std::malloc(bytes == 0 ? 1 : bytes);
    if (small == nullptr) throw std::bad_alloc();
    return small;
  }
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (p == nullptr) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
  // Advice only: where it is refused (no THP, "never") the pages are ordinary, nothing else.
  (void)madvise(p, rounded, MADV_HUGEPAGE);
#endif
  return p;
}

}  // namespace mote::detail
