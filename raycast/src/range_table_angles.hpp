#pragma once
/// \file
/// Internal: which table direction stands for a ray's direction (range_table_query.cpp).

#include <cmath>
#include <cstddef>

namespace mote::detail {

/// The table angle nearest to index a_real, which callers keep in [0, 2 * n); anything else
/// finite (an index wrapped with a rounding error, or a huge angle whose wrap lost precision)
/// is reduced first, so the cast below never sees a value out of int's range.
inline std::size_t nearest_angle(double a_real, int n) noexcept {
  if (!(a_real >= 0.0 && a_real < 2.0 * n)) {
    a_real = std::fmod(a_real, static_cast<double>(n));
    if (a_real < 0.0) a_real += n;
    if (!(a_real >= 0.0 && a_real < n)) a_real = 0.0;  // NaN: callers never pass one
  }
  int a = static_cast<int>(a_real + 0.5);
  if (a >= n) a -= n;
  if (a >= n) a -= n;
  return static_cast<std::size_t>(a);
}

}  // namespace mote::detail
