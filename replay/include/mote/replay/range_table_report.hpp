#pragma once
/// \file
/// What a beam model's range table cost and how far it is from exact casting, for
/// `mote info --map` and report.json (issue 19).

#include <iosfwd>

#include "mote/engine/beam_model.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/raycast/range_table.hpp"
#include "mote/replay/report_json.hpp"

namespace mote::replay {

/// Rays of the accuracy check and their length: 100k rays measure a share to about 0.1%.
inline constexpr std::size_t kRangeTableCheckRays = 100000;
inline constexpr float kRangeTableCheckRange = 30.0F;  ///< m

/// A table's layout, build time and memory, and its error against Embree.
struct RangeTableSummary {
  RangeTableStats stats;
  RangeTableAccuracy accuracy;
  bool unknown_blocks = true;
};

/// Measures `table` against an Embree caster of the same grid (kRangeTableCheckRays rays of at
/// most kRangeTableCheckRange from free cells, seed 1). `options` are those the table was built
/// with.
[[nodiscard]] RangeTableSummary summarize_range_table(const OccupancyGrid& grid,
                                                      const RangeTable& table,
                                                      const RangeTableOptions& options);

/// Indented lines, as the replay summary prints its rows.
void print_range_table(std::ostream& out, const RangeTableSummary& s);

/// "range_table": {...} as a member of the current object.
void write_range_table_json(JsonWriter& json, const RangeTableSummary& s);

/// Where the beam model was asked for a table and casts exactly instead, why: one summary row
/// naming the lattice the budget gives, its spacing and sigma_hit's. Nothing otherwise.
void print_beam_casting(std::ostream& out, const BeamCasting& casting, double resolution,
                        double budget_mb, double sigma_hit);

/// "beam_casting": {"table", "table_asked", "budget_lattice_cells", "max_lattice_cells"}.
void write_beam_casting_json(JsonWriter& json, const BeamCasting& casting);

}  // namespace mote::replay
