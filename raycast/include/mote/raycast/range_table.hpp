#pragma once
/// \file
/// A precomputed range table: for every lattice point of the map's non-blocking cells and each
/// of a fixed set of directions, the range to the first blocking cell, in 16-bit fixed point.
/// A cast is then one lookup per ray instead of an Embree traversal (range_libc's "giant lookup
/// table", Walsh and Karaman 2018, built here by a directional sweep instead of per-entry rays).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "mote/maps/occupancy_grid.hpp"
#include "mote/raycast/ray_batch.hpp"

namespace mote {

/// How the table is laid out and how much memory it may take.
struct RangeTableOptions {
  bool unknown_blocks = true;  ///< as RayCastOptions::unknown_blocks
  /// Directions over the full circle; the nearest one stands for a ray's direction. A multiple
  /// of 32 (one 64-byte line of entries), at least 32.
  int angles = 512;
  /// Upper bound of the table's bytes. The lattice coarsens (1, 2, 3, ... cells between lattice
  /// points) until the table fits; ConfigError when even the coarsest lattice does not. A
  /// coarser lattice reads fewer rays within a cell of exact casting (Willow at 256 MB: lattice
  /// 2, 86 % against 91 % on every cell) but tracked the shared logs as well (BENCHMARKS.md,
  /// "Range table").
  std::size_t memory_budget_bytes = std::size_t{256} << 20U;
  std::size_t particle_grain = 64;  ///< as RayCastOptions::particle_grain
};

/// What the table cost and how it is laid out.
struct RangeTableStats {
  int angles = 0;
  int lattice = 1;              ///< cells between lattice points (1: every cell)
  std::size_t points = 0;       ///< lattice points stored (those of non-blocking cells)
  std::size_t bytes = 0;        ///< everything the table holds: ranges, index, blocking mask
  double build_seconds = 0.0;   ///< wall clock of the sweep
  double units_per_cell = 8.0;  ///< fixed-point range units per cell
};

/// A ray caster answering from the table, with the RayCaster contract. A sensor inside or on the
/// boundary of a blocking cell reads 0 (the exact casters' start rule); a sensor off the map
/// falls back to the exact grid walk. Otherwise the range is the entry of the sensor's lattice
/// point at the nearest table direction, moved along the ray by the sensor's offset from the
/// lattice point (so a sensor anywhere in its cell reads the same wall, not the wall plus up to
/// half a cell). Deterministic: the table is a pure function of the grid and options.
class RangeTable {
 public:
  /// Builds the table in the caller's task arena. Throws ConfigError when options are invalid or
  /// the budget cannot hold any lattice (naming the bytes needed).
  explicit RangeTable(const OccupancyGrid& grid, RangeTableOptions options = {});
  ~RangeTable();
  RangeTable(RangeTable&&) noexcept;
  RangeTable& operator=(RangeTable&&) noexcept;
  RangeTable(const RangeTable&) = delete;
  RangeTable& operator=(const RangeTable&) = delete;

  /// Same contract as RayCaster::cast: read only, so concurrent casts on one table are safe.
  void cast(const RayBatch& batch, std::span<float> ranges) const;
  /// Same contract as RayCaster::cast_one.
  [[nodiscard]] float cast_one(Point2 origin, double angle, float max_range) const;

  [[nodiscard]] const RangeTableStats& stats() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

static_assert(RayCasterLike<RangeTable>);

/// The lattice (cells between points) a RangeTable of this grid with these options would have:
/// the finest whose table fits the budget, or 0 when not even the coarsest does (where the
/// constructor throws). Costs a pass over the grid per lattice tried, not a build. Throws
/// ConfigError when the options are invalid.
[[nodiscard]] int range_table_lattice(const OccupancyGrid& grid, const RangeTableOptions& options);

/// How far the table's ranges are from exact casting (in cells of the grid), over rays from
/// uniform points of free cells in uniform directions.
struct RangeTableAccuracy {
  std::size_t rays = 0;
  double within_one_cell = 0.0;   ///< share of rays with |table - exact| <= 1 cell
  double within_two_cells = 0.0;  ///< share with <= 2 cells
  double median_cells = 0.0;      ///< median of |table - exact|
  double p99_cells = 0.0;         ///< 99th percentile of |table - exact|
  double max_cells = 0.0;
  Point2 worst_origin{};     ///< map frame origin of the worst ray
  double worst_angle = 0.0;  ///< map frame angle (rad) of the worst ray
};

/// Compares the table with the Embree caster on `rays` rays of at most max_range (m) from
/// points drawn by a counter-based generator keyed by seed: the same result on every run.
[[nodiscard]] RangeTableAccuracy measure_range_table(const RangeTable& table,
                                                     const class RayCaster& exact,
                                                     const OccupancyGrid& grid, std::size_t rays,
                                                     float max_range, std::uint64_t seed = 1);

}  // namespace mote
