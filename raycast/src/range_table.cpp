#include "mote/raycast/range_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/core/parallel.hpp"
#include "range_table_impl.hpp"
#include "range_table_sweep.hpp"

// The range table's build: the lattice and the directional sweep (its queries are in
// range_table_query.cpp).
namespace mote {

namespace {

constexpr int kAngleGroup = 32;  // uint16 entries per 64-byte line: one build task's directions
constexpr int kMaxLattice = 32;
constexpr double kMaxUnitsPerCell = 16.0;

void check_options(const RangeTableOptions& o) {
  if (o.angles < kAngleGroup || o.angles % kAngleGroup != 0) {
    throw ConfigError("range table: angles must be a positive multiple of 32, got " +
                      std::to_string(o.angles));
  }
}

std::string megabytes(std::size_t bytes) {
  return std::to_string((bytes + (std::size_t{1} << 20U) - 1) >> 20U) + " MB";
}

/// The finest lattice whose table fits the budget, 0 when none up to kMaxLattice; `needed` gets
/// at least the bytes of the last lattice tried.
int fitting_lattice(const detail::CellMask& mask, const RangeTableOptions& o, std::size_t& needed) {
  const std::size_t cells =
      static_cast<std::size_t>(mask.width) * static_cast<std::size_t>(mask.height);
  const std::size_t free = detail::count_free_cells(mask);
  for (int lattice = 1; lattice <= kMaxLattice; ++lattice) {
    const auto blocks = static_cast<std::size_t>((mask.width + lattice - 1) / lattice) *
                        static_cast<std::size_t>((mask.height + lattice - 1) / lattice);
    // Every block holding a point is an upper bound, a block holding lattice^2 free cells a
    // lower one; count exactly (a pass over the map) only between the two.
    if (detail::table_bytes(blocks, blocks, cells, o.angles) <= o.memory_budget_bytes) {
      return lattice;
    }
    const auto area = static_cast<std::size_t>(lattice) * static_cast<std::size_t>(lattice);
    needed = detail::table_bytes((free + area - 1) / area, blocks, cells, o.angles);
    if (needed > o.memory_budget_bytes) continue;
    needed =
        detail::table_bytes(detail::count_lattice_points(mask, lattice), blocks, cells, o.angles);
    if (needed <= o.memory_budget_bytes) return lattice;
  }
  return 0;
}

/// fitting_lattice, or ConfigError naming the coarsest's size.
int choose_lattice(const detail::CellMask& mask, const RangeTableOptions& o) {
  std::size_t needed = 0;
  const int lattice = fitting_lattice(mask, o, needed);
  if (lattice > 0) return lattice;
  throw ConfigError("range table: a memory budget of " + megabytes(o.memory_budget_bytes) +
                    " holds no table of this map at " + std::to_string(o.angles) +
                    " angles; the coarsest lattice (" + std::to_string(kMaxLattice) +
                    " cells) needs at least " + megabytes(needed));
}

/// Fixed-point units per cell: as fine as 16 bits allow for the map's diagonal, at most 1/16.
double units_for(int width, int height) {
  const double diagonal = std::hypot(double(width), double(height)) + 2.0;
  const double units =
      std::min(kMaxUnitsPerCell, std::floor(double(detail::kNoHit - 1) / diagonal));
  if (units < 1.0) {
    throw ConfigError("range table: the map is too large for 16-bit ranges (diagonal " +
                      std::to_string(diagonal) + " cells, at most 65534)");
  }
  return units;
}
}  // namespace

void RangeTable::Impl::set_directions() {
  const auto angles = static_cast<std::size_t>(options.angles);
  for (std::size_t a = 0; a < angles; ++a) {
    const double phi =
        2.0 * std::numbers::pi * static_cast<double>(a) / static_cast<double>(angles);
    cos_a.push_back(static_cast<float>(detail::snap_direction(std::cos(phi))));
    sin_a.push_back(static_cast<float>(detail::snap_direction(std::sin(phi))));
  }
}

void RangeTable::Impl::fill_rows(const detail::CellMask& m, std::span<const float> px,
                                 std::span<const float> py, int lattice, std::uint16_t* out) const {
  const std::size_t points = px.size();
  const auto angles = static_cast<std::size_t>(options.angles);
  // One task per 32 directions: each fills a column per direction, then writes its own run of
  // 32 entries (64 bytes) in every point's row, so tasks write disjoint entries, share at most
  // the cache lines where their runs meet, and the result is the same for any thread count.
  par::for_each_chunk(angles, kAngleGroup, [&](std::size_t begin, std::size_t end) {
    const auto columns = huge_pages::uninitialized<std::uint16_t>((end - begin) * points);
    detail::SweepScratch scratch;
    for (std::size_t a = begin; a < end; ++a) {
      detail::sweep_direction(m, px, py, lattice, cos_a[a], sin_a[a], stats.units_per_cell, scratch,
                              {columns.get() + (a - begin) * points, points});
    }
    for (std::size_t p = 0; p < points; ++p) {
      std::uint16_t* row = out + p * angles;
      for (std::size_t a = begin; a < end; ++a) row[a] = columns[(a - begin) * points + p];
    }
  });
}

void RangeTable::Impl::build() {
  const auto start = std::chrono::steady_clock::now();
  const detail::CellMask m = mask();
  set_directions();
  stats.angles = options.angles;
  stats.units_per_cell = units_for(width, height);
  layout = detail::make_layout(m, choose_lattice(m, options));
  const std::size_t points = layout.points();
  for (const std::uint32_t cell : layout.cell_of_slot) {
    point_x.push_back(static_cast<float>(cell % static_cast<std::uint32_t>(width)) + 0.5F);
    point_y.push_back(static_cast<float>(cell / static_cast<std::uint32_t>(width)) + 0.5F);
  }
  // Not zero-filled: fill_rows writes every entry, and touches the table's pages first in
  // parallel (the serial fill was 4 % of an Intel build's perf samples). On 2 MB pages, as are
  // the tasks' columns: paired runs of the Intel build, 1.13-1.16 s against 1.54-1.59 s on 4 KB
  // pages (bench_raycast, RangeTable_Build).
  ranges =
      huge_pages::uninitialized<std::uint16_t>(points * static_cast<std::size_t>(options.angles));
  fill_rows(m, point_x, point_y, layout.lattice, ranges.get());
  stats.lattice = layout.lattice;
  stats.points = points;
  stats.bytes =
      detail::table_bytes(points, layout.slot_of_block.size(), blocking.size(), options.angles);
  stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

RangeTable::RangeTable(const OccupancyGrid& grid, RangeTableOptions options)
    : impl_(std::make_unique<Impl>()) {
  check_options(options);
  impl_->width = grid.width();
  impl_->height = grid.height();
  impl_->resolution = static_cast<float>(grid.resolution());
  impl_->origin = grid.origin();
  impl_->options = options;
  impl_->blocking = detail::blocking_mask(grid, options.unknown_blocks);
  impl_->build();
}

int range_table_lattice(const OccupancyGrid& grid, const RangeTableOptions& options) {
  check_options(options);
  const std::vector<std::uint8_t> blocking = detail::blocking_mask(grid, options.unknown_blocks);
  const detail::CellMask mask{grid.width(), grid.height(), static_cast<float>(grid.resolution()),
                              blocking.data()};
  std::size_t needed = 0;
  return fitting_lattice(mask, options, needed);
}

RangeTable::~RangeTable() = default;
RangeTable::RangeTable(RangeTable&&) noexcept = default;
RangeTable& RangeTable::operator=(RangeTable&&) noexcept = default;

const RangeTableStats& RangeTable::stats() const noexcept { return impl_->stats; }

}  // namespace mote
