#pragma once
// Image decoders behind read_map_image (private to mote::maps). Each takes the whole file's
// bytes, so size claims in a header are checked against the real data before any allocation.

#include <string>
#include <string_view>

#include "mote/maps/map_loader.hpp"

namespace mote::detail {

/// Largest number of cells an OccupancyGrid holds (its free-cell index is 32-bit).
inline constexpr unsigned long long kMaxCells = 0xFFFFFFFFULL;

/// Netpbm gray or colour maps: P2, P5 (gray), P3, P6 (RGB), maxval 1..65535.
[[nodiscard]] MapImage decode_pnm(const std::string& file, std::string_view bytes);

/// PNG through libpng's simplified API: gray, gray+alpha, RGB, RGBA, palettes expanded.
[[nodiscard]] MapImage decode_png(const std::string& file, std::string_view bytes);

}  // namespace mote::detail
