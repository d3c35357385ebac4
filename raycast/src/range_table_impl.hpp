#pragma once
/// \file
/// Internal: the range table's state (RangeTable::Impl) and the query's working types, shared by
/// the build (range_table.cpp) and the queries (range_table_query.cpp).

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "embree_packets.hpp"
#include "huge_pages.hpp"
#include "mote/raycast/range_table.hpp"
#include "range_table_claims.hpp"
#include "range_table_layout.hpp"
#include "range_table_tiles.hpp"
#include "ray_bundles.hpp"
#include "ray_setup.hpp"
#include "wall_scene.hpp"

namespace mote {

namespace detail {

/// Lattice points near a sensor and their offsets from it (cells). Always nine entries, so the
/// choice among them is a fixed, branch-free loop; entry 0 is the sensor's own block and
/// missing neighbours carry a mask of all ones below the sign bit that keeps them from being
/// chosen (and keeps every key below 2^31, where signed and unsigned minima agree).
inline constexpr std::uint32_t kMissing = 0x7FFFFFFFU;

/// What RangeTable::Impl::read gives for an uncertified entry: no range, cast the ray exactly.
inline constexpr float kCastExactly = -1.0F;
/// What RangeTable::Impl::units_at gives for a ray that leaves the map without a hit.
inline constexpr float kLeavesMap = std::numeric_limits<float>::infinity();

struct Candidates {
  static constexpr std::size_t kCount = 9;
  std::array<std::uint32_t, kCount> slot{};
  std::array<float, kCount> wx{};
  std::array<float, kCount> wy{};
  std::array<std::uint32_t, kCount> missing{};
};

/// The entries a lookup reads: the entry of the chosen lattice point and the sensor's own, and
/// the offset along the ray (cells) from the sensor to each point. Chosen for all the beams of
/// a sensor before any is read, so that the choice (the lookup's cost) runs on vector lanes.
struct Choice {
  std::size_t entry = 0;      ///< at the table angle below the ray's
  std::size_t own_entry = 0;  ///< the sensor's own point, same angle
  float along = 0.0F;
  float own_along = 0.0F;
  float frac = 0.0F;        ///< where the ray's angle lies between entry's angle and the next (0-1)
  std::ptrdiff_t next = 1;  ///< entry + next: the next table angle (wraps at the row's end)
};

/// Per-beam working arrays of RangeTable::Impl::choose and ::confirm_beams, reused across the
/// sensors of one task.
struct BeamScratch {
  explicit BeamScratch(std::size_t beams)
      : angle(beams),
        frac(beams),
        dx(beams),
        dy(beams),
        key(beams),
        next(beams),
        nearest(beams),
        leaves(beams) {}
  std::vector<std::uint32_t> angle;  ///< table angle below the ray's
  std::vector<float> frac;           ///< the ray's angle past it, in steps (0-1)
  std::vector<float> dx;             ///< its direction
  std::vector<float> dy;
  std::vector<std::int32_t> key;  ///< the running minimum of the candidates' keys
  // The confirmed table's (ClaimBeams): the next table angle, the nearest confirmed claim and
  // whether every claim left the map.
  std::vector<std::uint32_t> next;
  std::vector<float> nearest;
  std::vector<std::uint32_t> leaves;
};

}  // namespace detail

struct RangeTable::Impl {
  int width = 0;
  int height = 0;
  float resolution = 1.0F;
  Pose2 origin;
  RangeTableOptions options;
  std::vector<std::uint8_t> blocking;
  /// The exact caster's scene, for the rays of uncertified entries.
  std::unique_ptr<detail::WallScene> walls;
  /// The map as bits, for casting the rays of uncertified entries in bundles (certify only).
  std::unique_ptr<detail::BitMask> bits;
  /// The map as bits along rows and along columns, for the confirmed table's claims on vector
  /// lanes (confirm only).
  std::unique_ptr<detail::CellBits> cell_bits;
  /// Whether those lanes can index this table and map (detail::claims_fit_lanes).
  bool claims_on_lanes = false;
  /// What the last prepare decided for cast_prepared: bundles (true) or Embree.
  mutable std::atomic<bool> prepared_bundles{false};
  detail::TableLayout layout;  ///< the lattice of a whole table (empty when tiled)
  /// Tiles built on first use, when the whole table at a lattice of every cell is over budget:
  /// then a slot is TileSet::slot of its cell, and `ranges` is the tiles' reservation.
  std::unique_ptr<detail::TileSet> tiles;
  detail::HugeArray<std::uint16_t> whole;  ///< the whole table's entries, when not tiled
  std::uint16_t* ranges = nullptr;         ///< ranges[slot * angles + a]
  std::size_t entries = 0;                 ///< points * angles
  std::vector<float> cos_a;                ///< direction of table angle a in the grid frame
  std::vector<float> sin_a;
  std::vector<float> point_x;  ///< lattice point of each slot, in cells
  std::vector<float> point_y;
  RangeTableStats stats;

  /// Whether some rays are cast exactly (with Embree on `walls`) even on a table's cells.
  [[nodiscard]] bool casts_exactly() const noexcept { return options.certify || options.confirm; }
  /// Confirmation is in effect (certification takes precedence).
  [[nodiscard]] bool confirms() const noexcept { return options.confirm && !options.certify; }
  [[nodiscard]] detail::CellMask mask() const noexcept {
    return {width, height, resolution, blocking.data()};
  }
  void build();
  /// A tiled table for the budget, or false when the budget or the system will not have one.
  bool build_tiled(const detail::CellMask& m);
  void set_directions();
  /// Sweeps every direction for the points (px, py) (cells) and writes point k's entries to row
  /// k of `out` (rows of options.angles entries).
  void fill_rows(const detail::CellMask& m, std::span<const float> px, std::span<const float> py,
                 int lattice, std::uint16_t* out) const;
  /// Builds a tile's entries (those of its non-blocking cells), certified when the table is.
  void build_tile(std::size_t tile) const;
  /// Makes resident the tiles that the on-map sensors of `rays` need (caller holds the mutex).
  void prepare_tiles(const detail::BatchRays& rays, const detail::CellMask& m) const;
  /// The lattice points of the sensor's block and its 8 neighbours, for a sensor at grid frame
  /// point (gx, gy) m in on-map cell (i, j).
  [[nodiscard]] detail::Candidates candidates(int i, int j, double gx, double gy) const noexcept;
  /// The same for a tiled table (a lattice of every cell): the sensor's cell and its 8
  /// neighbours that do not block.
  [[nodiscard]] detail::Candidates tile_candidates(int i, int j, double gx,
                                                   double gy) const noexcept;
  /// Which entries answer for each beam of one sensor, at table angle index
  /// heading + beam_index[b] (fractional, in [0, 2 * angles)). Inlined into cast_chunk: as a
  /// call the plain table's queries ran about 5 % slower (bench_raycast, paired runs).
  [[gnu::always_inline]] inline void choose(const detail::Candidates& c, double heading,
                                            std::span<const double> beam_index,
                                            detail::BeamScratch& scratch,
                                            std::span<detail::Choice> choices) const noexcept;
  /// The range (table units) entry reads at choice's angle, kLeavesMap or kCastExactly.
  [[nodiscard]] [[gnu::always_inline]] inline float units_at(
      std::size_t entry, const detail::Choice& choice) const noexcept;
  /// The range (m) that choice reads, or kCastExactly.
  [[nodiscard]] [[gnu::always_inline]] inline float read(const detail::Choice& choice,
                                                         float max_range) const noexcept;
  /// The confirmed ranges (m) of every beam of one sensor at grid frame point (gx, gy) m, whose
  /// beam b points along table angle index heading + beam_index[b] and grid frame direction
  /// dir(b); kCastExactly for a beam no entry confirms (RangeTableOptions::confirm).
  template <class Direction>
  void confirm_beams(const detail::Candidates& c, double gx, double gy, double heading,
                     std::span<const double> beam_index, const Direction& dir, float max_range,
                     detail::BeamScratch& scratch, float* out) const noexcept;
  [[nodiscard]] float cast_ray(const detail::GridRay& ray, double angle, float max_range) const;
  /// Casts particles [begin, end) of a batch; rays of uncertified entries go to `exact` (a
  /// Packet16), or nowhere when the table is not certified, but for the particles `bundles`
  /// groups (when given), whose rays stay at kCastExactly; their sensor frames, which grouping
  /// computed for every particle, are read from it instead of computed again.
  template <class Wrap, class Exact>
  void cast_chunk(const detail::BatchRays& rays, const detail::CellMask& m,
                  std::span<const double> beam_index, const Wrap& wrap, std::size_t begin,
                  std::size_t end, std::span<float> out_ranges, Exact* exact,
                  const detail::BundleGroups* bundles = nullptr) const;
  /// cast_chunk with the exact caster: rays of uncertified entries, queued in particle order
  /// within the chunk, so which rays share a packet depends on the grain only (design.md 3).
  /// Those of particles in `bundles` (when given) are left reading kCastExactly, for bundles.
  template <class Wrap>
  void cast_chunk_certified(const detail::BatchRays& rays, const detail::CellMask& m,
                            std::span<const double> beam_index, const Wrap& wrap, std::size_t begin,
                            std::size_t end, std::span<float> out_ranges,
                            const detail::BundleGroups* bundles) const {
    const detail::FlushDenormals denormals_off;
    detail::Packet16 exact(walls->scene(), rays.max_range(), out_ranges);
    cast_chunk(rays, m, beam_index, wrap, begin, end, out_ranges, &exact, bundles);
    exact.flush();
    detail::check_embree_thread("casting rays");
  }
  /// Bytes of what casts exactly beside the table: the Embree scene and the bit masks.
  [[nodiscard]] std::size_t exact_bytes() const noexcept {
    return (walls ? walls->bytes() : 0) + (bits ? bits->bytes() : 0) +
           (cell_bits ? cell_bits->bytes() : 0);
  }
};

}  // namespace mote
