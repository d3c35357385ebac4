#include "huge_pages.hpp"

#include <cstdint>
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
  if (bytes < kHugePage) {  // a build task's columns for a tile: not worth a huge page
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

#if defined(__linux__)
void* reserve_address_space(std::size_t bytes) noexcept {
  // MAP_NORESERVE: the reservation is address space only (a 4000 x 4000 map reserves 16 GB);
  // only built tiles take memory. Over-reserve a huge page to align the start.
  const std::size_t span = bytes + kHugePage;
  void* raw = mmap(nullptr, span, PROT_READ | PROT_WRITE,
                   MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (raw == MAP_FAILED) return nullptr;
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (start + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > start) munmap(raw, aligned - start);
  const std::size_t tail = span - (aligned - start) - bytes;
  if (tail > 0) munmap(reinterpret_cast<void*>(aligned + bytes), tail);
  (void)madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
}

void release_address_space(void* p, std::size_t bytes) noexcept {
  if (p != nullptr) munmap(p, bytes);
}

void discard_pages(void* p, std::size_t bytes) noexcept {
  constexpr std::uintptr_t kPage = 4096;
  const auto begin = (reinterpret_cast<std::uintptr_t>(p) + kPage - 1) / kPage * kPage;
  const auto end = (reinterpret_cast<std::uintptr_t>(p) + bytes) / kPage * kPage;
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_DONTNEED);
}
#else
void* reserve_address_space(std::size_t) noexcept { return nullptr; }
void release_address_space(void*, std::size_t) noexcept {}
void discard_pages(void*, std::size_t) noexcept {}
#endif

}  // namespace mote::detail
