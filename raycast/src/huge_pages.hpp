#pragma once
/// \file
/// Internal: uninitialized arrays of trivial values on transparent huge pages, for the range
/// table and its build's columns (hundreds of MB written once).

#include <cstddef>
#include <memory>
#include <type_traits>

namespace mote::detail {

struct FreeDeleter {
  void operator()(void* p) const noexcept;
};

template <class T>
using HugeArray = std::unique_ptr<T[], FreeDeleter>;

/// `bytes` rounded up to whole 2 MB pages, 2 MB aligned, advised for transparent huge pages
/// where the system has them. Not zeroed. Throws std::bad_alloc.
void* allocate_huge_bytes(std::size_t bytes);

/// n uninitialized values. Why: first touching the Intel table's 190 MB in 4 KB pages was 11 %
/// of a build's perf samples (the page-fault path of a virtual machine); 2 MB pages take 512
/// times fewer faults.
template <class T>
HugeArray<T> allocate_huge(std::size_t n) {
  static_assert(std::is_trivial_v<T>);
  return HugeArray<T>(static_cast<T*>(allocate_huge_bytes(n * sizeof(T))));
}

}  // namespace mote::detail
