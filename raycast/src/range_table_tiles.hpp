#pragma once
/// \file
/// Internal: a range table built in tiles on first use, for maps whose whole table at a lattice
/// of every cell does not fit the memory budget (issue 19: "tiles built on first use for maps
/// too large to hold whole").
///
/// The table's address space is reserved for every cell of the map (a dense row per cell, tile
/// by tile) but no page is touched until its tile is built, so memory follows the tiles held.
/// Before a cast the tiles its sensors need are made resident: built in tile order, evicting
/// the least recently used tiles that cast does not need when the budget is full. A tile the
/// budget cannot hold is absent for that cast and its sensors' rays are cast exactly. All of it
/// happens between casts, on the caller's thread order, so the answers are a pure function of
/// the grid, the options and the sequence of casts; a tile's entries are exactly those of the
/// whole table (the same sweep lines), so residency never changes a range.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <shared_mutex>
#include <span>
#include <vector>

namespace mote::detail {

class TileSet {
 public:
  /// Tile edge (cells): 64 x 64 cells at 512 angles is 4 MB, built in tens of milliseconds.
  static constexpr int kCells = 64;
  using Residency = std::uint8_t;
  using UseStamp = std::uint64_t;
  /// Bookkeeping held for every tile, resident or not: a residency flag and a last-use stamp.
  static constexpr std::size_t kBookkeepingBytes = sizeof(Residency) + sizeof(UseStamp);

  /// Tiles along a side of `cells` cells (the last one may be partial).
  [[nodiscard]] static constexpr std::size_t tiles_across(int cells) noexcept {
    return static_cast<std::size_t>((cells + kCells - 1) / kCells);
  }
  /// Tiles covering a map of width x height cells.
  [[nodiscard]] static constexpr std::size_t count_for(int width, int height) noexcept {
    return tiles_across(width) * tiles_across(height);
  }

  /// Reserves the address space. nullptr (no tiles: the caller coarsens the lattice instead)
  /// when the system will not reserve it or slots would not fit 32 bits.
  [[nodiscard]] static std::unique_ptr<TileSet> reserve(int width, int height, int angles,
                                                        std::size_t max_resident);
  ~TileSet();
  TileSet(const TileSet&) = delete;
  TileSet& operator=(const TileSet&) = delete;

  [[nodiscard]] std::size_t count() const noexcept { return resident_.size(); }
  [[nodiscard]] std::size_t max_resident() const noexcept { return max_resident_; }
  [[nodiscard]] std::size_t tile_bytes() const noexcept;
  [[nodiscard]] std::uint16_t* ranges() const noexcept { return ranges_; }
  /// The dense slot of on-map cell (i, j): its tile's first slot plus its place in the tile.
  [[nodiscard]] std::uint32_t slot(int i, int j) const noexcept {
    const auto ti = static_cast<std::uint32_t>(i / kCells);
    const auto tj = static_cast<std::uint32_t>(j / kCells);
    const auto tile = tj * static_cast<std::uint32_t>(tiles_w_) + ti;
    return tile * kCells * kCells + static_cast<std::uint32_t>((j % kCells) * kCells + i % kCells);
  }
  [[nodiscard]] std::size_t tile_of(int i, int j) const noexcept {
    return static_cast<std::size_t>(j / kCells) * static_cast<std::size_t>(tiles_w_) +
           static_cast<std::size_t>(i / kCells);
  }
  /// First cell (i, j) of a tile.
  [[nodiscard]] int first_i(std::size_t tile) const noexcept {
    return static_cast<int>(tile % static_cast<std::size_t>(tiles_w_)) * kCells;
  }
  [[nodiscard]] int first_j(std::size_t tile) const noexcept {
    return static_cast<int>(tile / static_cast<std::size_t>(tiles_w_)) * kCells;
  }
  /// Calls f(tile) for each tile holding a cell of the 3 x 3 cells around on-map cell (i, j):
  /// a sensor's candidate lattice points.
  template <class F>
  void for_each_around(int i, int j, F&& f) const {
    const int i0 = (i > 0 ? i - 1 : 0) / kCells;
    const int i1 = (i + 1 < width_ ? i + 1 : width_ - 1) / kCells;
    const int j0 = (j > 0 ? j - 1 : 0) / kCells;
    const int j1 = (j + 1 < height_ ? j + 1 : height_ - 1) / kCells;
    for (int tj = j0; tj <= j1; ++tj) {
      for (int ti = i0; ti <= i1; ++ti) {
        f(static_cast<std::size_t>(tj) * static_cast<std::size_t>(tiles_w_) +
          static_cast<std::size_t>(ti));
      }
    }
  }
  /// True when every tile around cell (i, j) is resident: its sensors may read the table.
  [[nodiscard]] bool covers(int i, int j) const noexcept {
    bool all = true;
    for_each_around(i, j, [&](std::size_t t) { all = all && resident_[t] != 0; });
    return all;
  }
  /// Makes the tiles listed in `needed` (ascending) resident, in that order, with build(tile)
  /// for each one not yet built; returns how many it built. The caller holds mutex()
  /// exclusively.
  template <class Build>
  std::size_t ensure(std::span<const std::uint32_t> needed, Build&& build);
  /// Held exclusively while tiles change (a cast that builds, prepare), shared by casts that
  /// only read (cast_prepared), from before their first read to after their last.
  [[nodiscard]] std::shared_mutex& mutex() const noexcept { return mutex_; }
  [[nodiscard]] std::size_t built() const noexcept { return built_; }

 private:
  TileSet() = default;
  /// The least recently used resident tile that `needed` does not list, or count() if none.
  [[nodiscard]] std::size_t victim(std::span<const std::uint32_t> needed) const noexcept;
  void evict(std::size_t tile) noexcept;

  int width_ = 0;
  int height_ = 0;
  int tiles_w_ = 0;
  int angles_ = 0;
  std::size_t max_resident_ = 0;
  std::uint16_t* ranges_ = nullptr;
  std::size_t reserved_bytes_ = 0;
  std::vector<Residency> resident_;
  std::vector<UseStamp> last_used_;
  std::uint64_t casts_ = 0;
  std::size_t resident_count_ = 0;
  std::size_t built_ = 0;
  mutable std::shared_mutex mutex_;
};

template <class Build>
std::size_t TileSet::ensure(std::span<const std::uint32_t> needed, Build&& build) {
  ++casts_;
  std::size_t made = 0;
  for (const std::uint32_t t : needed) {
    if (resident_[t] == 0) {
      if (resident_count_ == max_resident_) {
        const std::size_t v = victim(needed);
        if (v == count()) continue;  // every resident tile is needed: t stays absent
        evict(v);
      }
      build(std::size_t{t});
      resident_[t] = 1;
      ++resident_count_;
      ++made;
    }
    last_used_[t] = casts_;
  }
  built_ += made;
  return made;
}

}  // namespace mote::detail
