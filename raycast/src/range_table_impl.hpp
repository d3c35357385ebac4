#pragma once
/// \file
/// Internal: the range table's state (RangeTable::Impl) and the query's working types, shared by
/// the build (range_table.cpp) and the queries (range_table_query.cpp).

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "mote/core/huge_pages.hpp"
#include "mote/raycast/range_table.hpp"
#include "range_table_layout.hpp"
#include "ray_setup.hpp"

namespace mote {

namespace detail {

/// Lattice points near a sensor and their offsets from it (cells). Always nine entries, so the
/// choice among them is a fixed, branch-free loop; entry 0 is the sensor's own block and
/// missing neighbours carry a mask of all ones below the sign bit that keeps them from being
/// chosen (and keeps every key below 2^31, where signed and unsigned minima agree).
inline constexpr std::uint32_t kMissing = 0x7FFFFFFFU;

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
  std::size_t entry = 0;      ///< at the table angle nearest the ray's
  std::size_t own_entry = 0;  ///< the sensor's own point, same angle
  float along = 0.0F;
  float own_along = 0.0F;
};

/// Per-beam working arrays of RangeTable::Impl::choose, reused across the sensors of one task.
struct BeamScratch {
  explicit BeamScratch(std::size_t beams) : angle(beams), dx(beams), dy(beams), key(beams) {}
  std::vector<std::uint32_t> angle;  ///< table angle nearest the ray's
  std::vector<float> dx;             ///< its direction
  std::vector<float> dy;
  std::vector<std::int32_t> key;  ///< the running minimum of the candidates' keys
};

}  // namespace detail

struct RangeTable::Impl {
  int width = 0;
  int height = 0;
  float resolution = 1.0F;
  Pose2 origin;
  RangeTableOptions options;
  std::vector<std::uint8_t> blocking;
  detail::TableLayout layout;
  std::unique_ptr<std::uint16_t[]> ranges;  ///< ranges[slot * angles + a]
  std::vector<float> cos_a;                 ///< direction of table angle a in the grid frame
  std::vector<float> sin_a;
  std::vector<float> point_x;  ///< lattice point of each slot, in cells
  std::vector<float> point_y;
  RangeTableStats stats;

  [[nodiscard]] detail::CellMask mask() const noexcept {
    return {width, height, resolution, blocking.data()};
  }
  void build();
  void set_directions();
  /// Sweeps every direction for the points (px, py) (cells) and writes point k's entries to row
  /// k of `out` (rows of options.angles entries).
  void fill_rows(const detail::CellMask& m, std::span<const float> px, std::span<const float> py,
                 int lattice, std::uint16_t* out) const;
  /// The lattice points of the sensor's block and its 8 neighbours, for a sensor at grid frame
  /// point (gx, gy) m in on-map cell (i, j).
  [[nodiscard]] detail::Candidates candidates(int i, int j, double gx, double gy) const noexcept;
  /// Which entries answer for each beam of one sensor, at table angle index
  /// heading + beam_index[b] (fractional, in [0, 2 * angles)). Inlined into cast_chunk: as a
  /// call the queries ran about 5 % slower (bench_raycast, paired runs).
  [[gnu::always_inline]] inline void choose(const detail::Candidates& c, double heading,
                                            std::span<const double> beam_index,
                                            detail::BeamScratch& scratch,
                                            std::span<detail::Choice> choices) const noexcept;
  /// The range (m) that choice reads.
  [[nodiscard]] [[gnu::always_inline]] inline float read(const detail::Choice& choice,
                                                         float max_range) const noexcept;
  [[nodiscard]] float cast_ray(const detail::GridRay& ray, double angle, float max_range) const;
  /// Casts particles [begin, end) of a batch.
  template <class Wrap>
  void cast_chunk(const detail::BatchRays& rays, const detail::CellMask& m,
                  std::span<const double> beam_index, const Wrap& wrap, std::size_t begin,
                  std::size_t end, std::span<float> out_ranges) const;
};

}  // namespace mote
