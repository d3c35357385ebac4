// `mote info LOG`: what a recorded log holds (logs/include/mote/logs/log_info.hpp).
// `mote info --map MAP.yaml`: the map, and what the beam model's range table costs on it.
#include <array>
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "mote/logs/log_info.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/replay/range_table_report.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 9> kFlags{{
    {"map", "MAP.yaml", "instead of a LOG: the map, and the beam model's range table built on it"},
    {"range-table-angles", "N", "with --map: table directions, a multiple of 32 (default 512)"},
    {"range-table-budget-mb", "MB", "with --map: table memory budget (default 256)"},
    {"unknown-blocks", "",
     "with --map: unknown cells stop rays, as with --nav2-defaults (default: "
     "they do not, as the beam model runs with no flags)"},
    {"sigma-hit", "M", "with --map: the beam model's sigma_hit, which bounds the lattice (0.2)"},
    {"scan-topic", "TOPIC", "ROS bags: the LaserScan topic (default: the only one)"},
    {"odom-topic", "TOPIC", "ROS bags: the Odometry topic (default: the only one, or tf)"},
    {"odom-frame", "FRAME", "ROS bags: odometry frame when odometry comes from tf (default odom)"},
    {"base-frame", "FRAME", "ROS bags: robot base frame (default: the odometry's child frame)"},
}};

constexpr std::string_view kUsage = "mote info LOG [flags] | mote info --map MAP.yaml [flags]";
constexpr std::string_view kAbout =
    "Prints what a recorded log holds: format, storage and compression, duration, message\n"
    "counts per topic and type, the laser (beams, field of view, range limits, mounting pose)\n"
    "and the tf frames. LOG: CARMEN .clf/.log, ROS 1 .bag, rosbag2 folder, .mcap or .db3.\n"
    "With --map: the map's size and cells, and the range table (ray_casting: table) built on\n"
    "it: layout, memory, build time and its error against exact Embree casting. Where the\n"
    "budget holds the table only on a lattice coarser than sqrt(2) sigma_hit, the beam model\n"
    "casts exactly instead, and the table is not built.";

int map_info(const ParsedArgs& args) {
  const std::string path = args.required("map");
  const OccupancyGrid grid = load_map(path);
  RangeTableOptions options;
  options.unknown_blocks = args.has("unknown-blocks") || LocalizerConfig{}.unknown_cells_block_rays;
  if (auto n = args.integer("range-table-angles", 32, 1 << 16)) {
    options.angles = static_cast<int>(*n);
  }
  if (auto mb = args.real("range-table-budget-mb", 1e-6, 1048576.0)) {
    options.memory_budget_bytes = static_cast<std::size_t>(*mb * 1048576.0);
  }
  const double sigma_hit = args.real("sigma-hit", 1e-6, 1e6).value_or(LocalizerConfig{}.sigma_hit);
  std::cout << "map " << path << "\n  " << grid.width() << " x " << grid.height() << " cells of "
            << grid.resolution() << " m, " << grid.free_cell_count() << " free\n";
  BeamCasting casting{.table_asked = true,
                      .budget_lattice = range_table_lattice(grid, options),
                      .max_lattice = max_table_lattice(sigma_hit, grid.resolution())};
  casting.table = casting.budget_lattice > 0 && casting.budget_lattice <= casting.max_lattice;
  if (!casting.table) {
    replay::print_beam_casting(std::cout, casting, grid.resolution(),
                               static_cast<double>(options.memory_budget_bytes) / 1048576.0,
                               sigma_hit);
    return 0;
  }
  const RangeTable table(grid, options);
  replay::print_range_table(std::cout, replay::summarize_range_table(grid, table, options));
  return 0;
}

}  // namespace

int info_command(std::span<char* const> words) {
  if (words.empty() || std::string_view(words[0]).starts_with("--")) {
    const ParsedArgs args = parse_args("info", words, kFlags);
    if (args.has("help")) {
      print_help(std::cout, kUsage, kAbout, kFlags);
      return 0;
    }
    if (args.has("map")) return map_info(args);
    throw UsageError("mote info: expects a LOG (see mote info --help)");
  }
  const ParsedArgs args = parse_args("info", words.subspan(1), kFlags);
  if (args.has("map")) throw UsageError("mote info: give a LOG or --map MAP.yaml, not both");
  logs::ReaderOptions options;
  if (auto t = args.text("scan-topic")) options.scan_topic = *t;
  if (auto t = args.text("odom-topic")) options.odom_topic = *t;
  if (auto f = args.text("odom-frame")) options.odom_frame = *f;
  if (auto f = args.text("base-frame")) options.base_frame = *f;
  logs::print_log_info(std::cout, logs::describe_log(words[0], options));
  return 0;
}

}  // namespace mote::tool
