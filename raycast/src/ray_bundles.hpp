#pragma once
/// \file
/// Internal: exact casting of coherent rays in bundles. A tracking filter's particles sit close
/// together with close headings, so the rays of one beam from a group of them sweep a narrow
/// wedge of the map. One pass over the wedge's cells, in strips across its major axis in order
/// of distance, finds the blocking cells any of the rays could meet (64 cells a read, from a
/// bit mask); each ray is tested only against the blocks near its own path (a slab test), and
/// is done after the first strip in which it hits. The ranges are the exact casters': the
/// first wall on each ray, with walls reaching kSnapDistance past their ends as theirs do,
/// whatever the grouping and the thread count.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "ray_setup.hpp"

namespace mote::detail {

/// The blocking mask one bit a cell, twice: rows (bit i of row j is cell (i, j)) and columns
/// (bit j of column i), so a bundle reads the cells across its path 64 at a time along either
/// axis. A zero word closes every line, so a read of 64 bits from any cell on it stays inside.
class BitMask {
 public:
  explicit BitMask(const CellMask& mask);
  /// Cells [first, first + 64) of major line `line` as bits (cells past the line's end are 0):
  /// across column `line` when `along_x` (a bundle travelling along x), else across row `line`.
  [[nodiscard]] std::uint64_t bits(bool along_x, int line, int first) const noexcept;
  [[nodiscard]] std::size_t bytes() const noexcept {
    return (rows_.size() + columns_.size()) * sizeof(std::uint64_t);
  }

 private:
  std::size_t row_words_ = 0;
  std::size_t column_words_ = 0;
  std::vector<std::uint64_t> rows_;
  std::vector<std::uint64_t> columns_;
};

/// How sensors make one group: those in one block of `block_cells` cells a side whose headings
/// fall in one of `heading_bins` bins over the circle. Finer groups make narrower wedges (fewer
/// blocks tested per ray), coarser ones fuller bundles (a strip's cells read for more rays).
struct BundleGrouping {
  int heading_bins = 720;
  int block_cells = 16;
};

/// The batch's particles grouped for bundles. Particle order within a group and the groups'
/// order depend on the particles' indices only.
struct BundleGroups {
  std::vector<SensorFrame> sensors;      ///< every particle's, computed once
  std::vector<std::uint32_t> particles;  ///< grouped; group g is [starts[g], starts[g + 1])
  std::vector<std::uint32_t> starts;
  std::vector<std::uint8_t> grouped;  ///< per particle: 1 when in a group

  [[nodiscard]] std::size_t count() const noexcept {
    return starts.empty() ? 0 : starts.size() - 1;
  }
  [[nodiscard]] double mean_size() const noexcept {
    return count() == 0 ? 0.0
                        : static_cast<double>(particles.size()) / static_cast<double>(count());
  }
  [[nodiscard]] std::span<const std::uint32_t> group(std::size_t g) const noexcept {
    return std::span(particles).subspan(starts[g], starts[g + 1] - starts[g]);
  }
};

/// Groups of at least `min_size` sensors that are on the map, finite and not in a blocking
/// cell; every other particle is left to the caller (grouped[p] == 0). Parallel over particles.
[[nodiscard]] BundleGroups group_for_bundles(const BatchRays& rays, const CellMask& mask,
                                             std::size_t grain, std::size_t min_size,
                                             BundleGrouping grouping = {});

/// A group's working arrays, reused from group to group by one task.
struct BundleScratch {
  std::vector<float> gx, gy;  ///< the group's sensors (cells)
  // The current beam's rays (the group's sensors `chosen`, all or those left to cast), in no
  // order: origin and direction as traced (m, doubles), the same in cells, key and bucket,
  // range found (cells).
  std::vector<std::uint32_t> chosen;
  std::vector<double> qx, qy, qdx, qdy;
  std::vector<float> ox, oy, dx, dy, key, cells;
  std::vector<std::uint32_t> bucket, order, fill;
  // The open rays in buckets of key (bucket b is [starts[b], starts[b + 1])): origin,
  // direction's reciprocal, the near-miss window (near_window) along the ray per axis, nearest
  // hit so far, the ray's place among the beam's rays.
  std::vector<float> px, py, ix, iy, wx, wy, best;
  std::vector<std::uint32_t> ray_of, starts;
  float key_origin = 0.0F;  ///< the lowest key, floored
  float key_top = 0.0F;     ///< the highest
  struct Box {
    float x0, x1, y0, y1;  ///< cells
  };
  std::vector<Box> boxes;
};

/// Beams [first, second) of a batch.
using BeamRange = std::pair<std::size_t, std::size_t>;

/// Casts the group's rays of `beams` into `ranges` (particle-major, metres): those of every
/// particle, or with `only` just the rays whose range reads *only (those a table left to exact
/// casting).
void cast_bundle_group(const BatchRays& rays, const CellMask& mask, const BitMask& bits,
                       const BundleGroups& groups, std::size_t group, std::span<float> ranges,
                       BundleScratch& scratch, BeamRange beams,
                       std::optional<float> only = std::nullopt);

/// cast_bundle_group for every group and beam, parallel: one task per group and block of beams,
/// so what a task does depends on neither the thread count nor the grain, and every ray's range
/// on nothing but the ray.
void cast_bundles(const BatchRays& rays, const CellMask& mask, const BitMask& bits,
                  const BundleGroups& groups, std::span<float> ranges,
                  std::optional<float> only = std::nullopt);

/// The mean size of the groups a cast forms from which casting a certified table's uncertified
/// third of the rays in bundles beats Embree: the beam model tracking on Intel at 10k particles
/// gains 1.2-1.3 times (its whole set's groups hold about 170; the parts' it casts fewer, not
/// measured); bench_raycast's tracking cloud (0.2 rad of heading) forms groups of about 5 and
/// loses. Between them, not measured closer: the break-even of casting every ray.
inline constexpr double kBundlesPayForSomeRays = 32.0;

/// Casts prepared on a whole set are made in parts of this many consecutive particles, each
/// grouping its own sensors: the engine weighs its particles in tasks of that many (its default
/// grain).
inline constexpr std::size_t kPreparedPart = 4096;

/// The mean size of the groups that parts of `part` consecutive particles form, estimated on
/// two of them (the first and the middle one). A set whose sensors gather only as a whole (a
/// global set after the first updates: few headings, but every part holding particles from all
/// over the map) has small groups in each part, where bundles lose to Embree four times over.
[[nodiscard]] double part_group_size(const BatchRays& rays, const CellMask& mask, std::size_t part);

/// Whether the parts of a whole batch (kPreparedPart particles each) gather into groups of at
/// least `min_mean` on average: the choice a caster makes once per update, before casting the
/// batch in parts.
[[nodiscard]] bool bundles_pay(const BatchRays& rays, const CellMask& mask, double min_mean);

/// The groups' mean size from which casting every ray in bundles beats Embree (measured, a
/// scratch program casting 10k-sensor clouds whole, 2 threads: on Intel even at groups of 27,
/// 1.2-1.5 times Embree's speed at 36-51, twice at 143-385, 0.7 at 16; on Willow 1.2 at 27,
/// 0.9 at 16).
inline constexpr double kBundlesPayForEveryRay = 32.0;

}  // namespace mote::detail
