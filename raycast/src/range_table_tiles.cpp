#include "range_table_tiles.hpp"

#include <algorithm>
#include <limits>

#include "huge_pages.hpp"

namespace mote::detail {

std::unique_ptr<TileSet> TileSet::reserve(int width, int height, int angles,
                                          std::size_t max_resident) {
  const std::size_t tiles_w = tiles_across(width);
  const std::size_t tiles = count_for(width, height);
  const std::size_t slots = tiles * kCells * kCells;
  if (slots > std::numeric_limits<std::uint32_t>::max() || max_resident == 0) return nullptr;
  const std::size_t bytes = slots * static_cast<std::size_t>(angles) * sizeof(std::uint16_t);
  void* region = reserve_address_space(bytes);
  if (region == nullptr) return nullptr;
  std::unique_ptr<TileSet> s(new TileSet());
  s->width_ = width;
  s->height_ = height;
  s->tiles_w_ = static_cast<int>(tiles_w);
  s->angles_ = angles;
  s->max_resident_ = max_resident;
  s->ranges_ = static_cast<std::uint16_t*>(region);
  s->reserved_bytes_ = bytes;
  s->resident_.assign(tiles, 0);
  s->last_used_.assign(tiles, 0);
  return s;
}

TileSet::~TileSet() { release_address_space(ranges_, reserved_bytes_); }

std::size_t TileSet::tile_bytes() const noexcept {
  return std::size_t{kCells} * kCells * static_cast<std::size_t>(angles_) * sizeof(std::uint16_t);
}

std::size_t TileSet::victim(std::span<const std::uint32_t> needed) const noexcept {
  std::size_t best = count();
  for (std::size_t t = 0; t < count(); ++t) {
    if (resident_[t] == 0 || std::binary_search(needed.begin(), needed.end(), t)) continue;
    if (best == count() || last_used_[t] < last_used_[best]) best = t;
  }
  return best;
}

void TileSet::evict(std::size_t tile) noexcept {
  discard_pages(reinterpret_cast<char*>(ranges_) + tile * tile_bytes(), tile_bytes());
  resident_[tile] = 0;
  --resident_count_;
}

}  // namespace mote::detail
