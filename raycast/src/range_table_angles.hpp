#pragma once
/// \file
/// Internal: which table directions stand for a ray's direction (range_table_query.cpp,
/// range_table_confirm.hpp).

#include <algorithm>
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

/// The table angle at or below index a_real, and a_real's distance past it (steps, in [0, 1)).
/// Callers keep a_real in [0, 2 * n); anything else finite (an index wrapped with a rounding
/// error, or a huge angle whose wrap lost precision) is reduced first, so the cast below never
/// sees a value out of int's range.
inline std::size_t angle_below(double a_real, int n, float& frac) noexcept {
  if (!(a_real >= 0.0 && a_real < 2.0 * n)) {
    a_real = std::fmod(a_real, static_cast<double>(n));
    if (a_real < 0.0) a_real += n;
    if (!(a_real >= 0.0 && a_real < n)) a_real = 0.0;  // NaN: callers never pass one
  }
  int a = static_cast<int>(a_real);
  frac = std::clamp(static_cast<float>(a_real - a), 0.0F, 1.0F);
  if (a >= n) a -= n;
  if (a >= n) a -= n;
  return static_cast<std::size_t>(a);
}

}  // namespace mote::detail
