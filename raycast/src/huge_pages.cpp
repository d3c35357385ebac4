#include "huge_pages.hpp"

#include <cstdlib>
#include <new>

#include "mote/core/huge_pages.hpp"

namespace mote::detail {

namespace {
constexpr std::size_t kHugePage = huge_pages::kPageBytes;
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
  huge_pages::advise(p, rounded);
  return p;
}

}  // namespace mote::detail
