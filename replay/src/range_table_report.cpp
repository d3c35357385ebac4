#include "mote/replay/range_table_report.hpp"

#include <iomanip>
#include <numbers>
#include <ostream>
#include <sstream>
#include <string>

#include "mote/raycast/ray_caster.hpp"

namespace mote::replay {

namespace {

std::string fixed(double v, int precision) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(precision) << v;
  return s.str();
}

void line(std::ostream& out, const char* name, const std::string& value) {
  out << "  " << std::left << std::setw(22) << name << value << '\n';
}

}  // namespace

RangeTableSummary summarize_range_table(const OccupancyGrid& grid, const RangeTable& table,
                                        const RangeTableOptions& options) {
  const RayCaster exact(grid, RayCastOptions{.unknown_blocks = options.unknown_blocks});
  return {.stats = table.stats(),
          .accuracy = measure_range_table(table, exact, grid, kRangeTableCheckRays,
                                          kRangeTableCheckRange, 1),
          .unknown_blocks = options.unknown_blocks};
}

void print_range_table(std::ostream& out, const RangeTableSummary& s) {
  const RangeTableStats& t = s.stats;
  const RangeTableAccuracy& a = s.accuracy;
  line(out, "range table",
       std::to_string(t.angles) + " angles, lattice " + std::to_string(t.lattice) + " cell(s), " +
           std::to_string(t.points) + " points");
  line(out, "  memory", fixed(static_cast<double>(t.bytes) / 1048576.0, 1) + " MB");
  line(out, "  build", fixed(t.build_seconds, 3) + " s");
  line(out, "  vs Embree",
       fixed(100.0 * a.within_one_cell, 2) + " % within 1 cell, " +
           fixed(100.0 * a.within_two_cells, 2) + " % within 2 (" + std::to_string(a.rays) +
           " rays from free cells, up to " + fixed(kRangeTableCheckRange, 0) + " m)");
  line(out, "  error (cells)",
       "median " + fixed(a.median_cells, 3) + ", p99 " + fixed(a.p99_cells, 2) + ", max " +
           fixed(a.max_cells, 1) + " from (" + fixed(a.worst_origin.x, 3) + ", " +
           fixed(a.worst_origin.y, 3) + ") at " + fixed(a.worst_angle, 4) + " rad");
}

void write_range_table_json(JsonWriter& json, const RangeTableSummary& s) {
  const RangeTableStats& t = s.stats;
  const RangeTableAccuracy& a = s.accuracy;
  json.key("range_table").begin_object();
  json.member("angles", t.angles).member("lattice_cells", t.lattice);
  json.member("points", std::uint64_t{t.points}).member("bytes", std::uint64_t{t.bytes});
  json.member("build_s", t.build_seconds).member("unknown_blocks", s.unknown_blocks);
  json.key("vs_embree").begin_object();
  json.member("rays", std::uint64_t{a.rays});
  json.member("max_range_m", static_cast<double>(kRangeTableCheckRange));
  json.member("within_one_cell", a.within_one_cell);
  json.member("within_two_cells", a.within_two_cells);
  json.member("median_cells", a.median_cells).member("p99_cells", a.p99_cells);
  json.member("max_cells", a.max_cells);
  json.member("worst_x", a.worst_origin.x).member("worst_y", a.worst_origin.y);
  json.member("worst_angle", a.worst_angle);
  json.end_object();
  json.end_object();
}

void print_beam_casting(std::ostream& out, const BeamCasting& casting, double resolution,
                        double budget_mb, double sigma_hit) {
  if (!casting.table_asked || casting.table) return;
  const std::string budget = fixed(budget_mb, budget_mb < 10.0 ? 1 : 0) + " MB";
  const std::string why = casting.budget_lattice == 0
                              ? "no lattice of the range table fits " + budget
                              : "the range table fits " + budget + " only on a lattice of " +
                                    std::to_string(casting.budget_lattice) + " cells (" +
                                    fixed(casting.budget_lattice * resolution, 2) +
                                    " m), coarser than sqrt(2) sigma_hit (" +
                                    fixed(std::numbers::sqrt2 * sigma_hit, 2) + " m)";
  line(out, "ray casting", "exact: " + why);
}

void write_beam_casting_json(JsonWriter& json, const BeamCasting& casting) {
  json.key("beam_casting").begin_object();
  json.member("table", casting.table).member("table_asked", casting.table_asked);
  json.member("budget_lattice_cells", casting.budget_lattice);
  json.member("max_lattice_cells", casting.max_lattice);
  json.end_object();
}

}  // namespace mote::replay
