// `mote replay`: flags -> ReplayOptions (config file first, flags over it) -> run -> outputs.
#include <array>
#include <iostream>
#include <numbers>
#include <optional>
#include <utility>

#include "args.hpp"
#include "commands.hpp"
#include "mote/engine/node_params.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/replay/report.hpp"
#include "mote/replay/verdict.hpp"
#include "mote/replay/viewer.hpp"
#include "progress.hpp"
#include "run_config.hpp"

namespace mote::tool {
namespace {

constexpr std::array<FlagSpec, 25> kFlags{{
    {"map", "MAP.yaml", "map_server map (required)"},
    {"log", "LOG",
     "recorded log: CARMEN .clf/.log, ROS 1 .bag, or ROS 2 (rosbag2 folder, .mcap, .db3) "
     "(required)"},
    {"out", "DIR", "output folder, created if missing (required)"},
    {"reference", "REF.tum", "reference trajectory (TUM); enables accuracy figures"},
    {"config", "CONFIG.yaml",
     "LocalizerConfig YAML (flat amcl names, or a nav2 params file as it is: its values over "
     "mote's adaptive defaults; set_initial_pose starts at its initial_pose)"},
    {"nav2-defaults", "",
     "nav2_amcl's defaults instead of mote's adaptive ones (fixed tempering 1, no recovery, "
     "fixed odometry noise, 500-2000 particles); with --config, under the file's keys"},
    {"model", "NAME", "likelihood_field or beam (default likelihood_field)"},
    {"particles", "N", "fixed particle count: min = max = N"},
    {"min-particles", "N", "KLD lower bound (default 500)"},
    {"max-particles", "N", "KLD upper bound and cap of the initial sets (default 500000)"},
    {"beams", "N", "beams used per scan (default 60)"},
    {"threads", "N", "worker threads, 0 = every core (default 0)"},
    {"seed", "N", "random seed (default 42)"},
    {"init", "MODE", "global, or reference (default: reference if given, else global)"},
    {"init-pose", "X,Y,THETA", "start around this pose (m, m, rad), 0.1 m / 5 deg std"},
    {"kidnapped-at", "STAMP",
     "s, stamp of a kidnapping (mote kidnap prints it): with --reference, reports how many "
     "updates after it the filter needs to be within 0.3 m of the reference for 20 updates"},
    {"laser-max-range", "M",
     "m, the laser's no-return reading for CARMEN FLASER logs, which do not record it, and the "
     "config's laser_max_range (default: inferred from the log's first scans)"},
    {"scan-topic", "TOPIC",
     "ROS bags: the sensor_msgs LaserScan topic (default: the only one; ROS 1: the first)"},
    {"odom-topic", "TOPIC",
     "ROS bags: the nav_msgs Odometry topic (default: the only one; none: odom -> base on tf)"},
    {"odom-frame", "FRAME", "ROS bags: odometry frame when odometry comes from tf (default odom)"},
    {"base-frame", "FRAME", "ROS bags: robot base frame (default: the odometry's child frame)"},
    {"lenient", "", "skip malformed log records (counted in the report) instead of failing"},
    {"quiet", "", "no summary table on stdout"},
    {"profile", "",
     "per-phase timing: percentiles and histograms in report.json, DIR/profile.folded (folded "
     "stacks, microseconds, for flamegraph.pl or speedscope) and a phase table"},
    {"viewer", "",
     "DIR/viewer.html: one self-contained page replaying particles, scan, estimate and "
     "reference over the map, with timelines of the update statistics (open DIR/viewer.html#t=N "
     "for update N)"},
}};

constexpr std::string_view kUsage =
    "mote replay --map MAP.yaml --log LOG --out DIR [--reference REF.tum] [flags]";
constexpr std::string_view kAbout =
    "Runs a recorded log through the particle filter and writes DIR/report.json (timings,\n"
    "accuracy, the verdict), DIR/trajectory.tum (estimate after every update), DIR/updates.csv\n"
    "and DIR/map.png. Exit status 0 when the run ends localized, 3 when it ends lost (the scans\n"
    "do not fit the map: a warning says so), 1 on an error, 2 on a usage error.";

int to_int(std::int64_t v) { return static_cast<int>(v); }

void apply_counts(const ParsedArgs& args, LocalizerConfig& c) {
  constexpr std::int64_t kMaxCount = 100'000'000;
  if (auto n = args.integer("min-particles", 1, kMaxCount)) c.min_particles = to_int(*n);
  if (auto n = args.integer("max-particles", 1, kMaxCount)) c.max_particles = to_int(*n);
  if (auto n = args.integer("particles", 1, kMaxCount))
    c.min_particles = c.max_particles = to_int(*n);
  if (auto n = args.integer("beams", 1, 100'000)) c.max_beams = to_int(*n);
  if (auto n = args.integer("threads", 0, 1024)) c.threads = to_int(*n);
  if (auto n = args.integer("seed", 0, INT64_MAX)) c.seed = static_cast<std::uint64_t>(*n);
}

void apply_model(const ParsedArgs& args, LocalizerConfig& c) {
  const auto model = args.text("model");
  if (!model) return;
  if (*model == "likelihood_field") {
    c.laser_model_type = LaserModel::kLikelihoodField;
  } else if (*model == "beam") {
    c.laser_model_type = LaserModel::kBeam;
  } else {
    throw args.error("model", "must be likelihood_field or beam, got '" + *model + "'");
  }
}

void apply_init(const ParsedArgs& args, replay::ReplayOptions& o) {
  if (args.has("init") && args.has("init-pose"))
    throw args.error("init", "and --init-pose exclude each other");
  if (args.has("init-pose")) {
    o.init = replay::InitMode::kPose;
    o.init_pose = *pose_flag(args, "init-pose");
  } else if (const auto mode = args.text("init")) {
    if (*mode == "global") {
      o.init = replay::InitMode::kGlobal;
    } else if (*mode == "reference" && !o.reference.empty()) {
      o.init = replay::InitMode::kAuto;
    } else {
      throw args.error("init",
                       "must be global, or reference with --reference; got '" + *mode + "'");
    }
  }
}

// nav2_amcl's set_initial_pose: the file's start pose, unless a flag or a reference says where
// to start.
void apply_file_start(const ParsedArgs& args, replay::ReplayOptions& o) {
  const auto path = args.text("config");
  if (!path || o.init != replay::InitMode::kAuto || !o.reference.empty()) return;
  const NodeParams node = read_node_params(*path);
  if (!node.set_initial_pose) return;
  o.init = replay::InitMode::kPose;
  o.init_pose = {node.initial_pose.x, node.initial_pose.y, wrap_angle(node.initial_pose.yaw)};
}

replay::ReplayOptions replay_options(const ParsedArgs& args, const LoadedConfig& config) {
  replay::ReplayOptions o;
  o.map = args.required("map");
  o.log = args.required("log");
  if (auto ref = args.text("reference")) o.reference = *ref;
  apply_init(args, o);
  apply_file_start(args, o);
  if (auto at = args.real("kidnapped-at", -1e12, 1e12)) {
    if (o.reference.empty()) throw args.error("kidnapped-at", "needs --reference");
    o.kidnapped_at = *at;
  }
  o.reader.lenient = args.has("lenient");
  if (auto t = args.text("scan-topic")) o.reader.scan_topic = *t;
  if (auto t = args.text("odom-topic")) o.reader.odom_topic = *t;
  if (auto f = args.text("odom-frame")) o.reader.odom_frame = *f;
  if (auto f = args.text("base-frame")) o.reader.base_frame = *f;
  o.config = config.config;
  apply_counts(args, o.config);
  if (auto m = args.real("laser-max-range", 0.01, 1e6)) {
    o.reader.carmen_max_range = static_cast<float>(*m);
    o.config.laser_max_range = *m;
  }
  apply_model(args, o.config);
  return o;
}

void print_config_summary(const char* command, const LoadedConfig& loaded,
                          const replay::ReplayOptions& options) {
  for (const std::string& line : config_summary(loaded))
    std::cout << "mote " << command << ": " << line << '\n';
  if (options.init == replay::InitMode::kPose) {
    const Pose2& p = options.init_pose;
    std::cout << "mote " << command << ": start: around " << p.x << ", " << p.y << ", " << p.theta
              << " (m, m, rad)\n";
  }
  std::cout.flush();
}

}  // namespace

replay::ReplayResult replay_and_report(replay::ReplayOptions options,
                                       const std::filesystem::path& out_dir,
                                       const replay::ReportOptions& report, bool viewer) {
  // A replay can take minutes: an --out that cannot be a folder fails before it, not after.
  replay::make_output_folder(out_dir);
  std::optional<replay::ViewerRecorder> recorder;
  if (viewer) {
    // The recorder quantizes against the map the run loads; loading it twice costs milliseconds.
    recorder.emplace(load_map(options.map));
    options.on_update = [&recorder](const Localizer& filter, const logs::ScanFrame& frame) {
      recorder->record(filter, frame);
    };
  }
  options.progress = make_progress(options.log, options.reader);
  replay::ReplayResult result = replay::run_replay(options);
  finish_progress(options.progress);
  replay::write_replay_outputs(out_dir, result, report);
  if (recorder) replay::write_viewer_html(out_dir / "viewer.html", result, recorder->recording());
  return result;
}

int warn_unless_localized(const char* command, const replay::ReplayResult& result) {
  const replay::RunVerdict verdict = replay::judge_run(result);
  if (!verdict.warning.empty()) {
    std::cerr << "mote " << command << ": warning: " << verdict.warning << '\n';
  }
  return replay::exit_status(verdict);
}

int replay_command(std::span<char* const> words) {
  const ParsedArgs args = parse_args("replay", words, kFlags);
  if (args.has("help")) {
    print_help(std::cout, kUsage, kAbout, kFlags);
    return 0;
  }
  const std::filesystem::path out = args.required("out");
  const replay::ReportOptions report{.profile = args.has("profile")};
  const LoadedConfig config = run_config(args, "replay");
  replay::ReplayOptions options = replay_options(args, config);
  if (!args.has("quiet")) print_config_summary("replay", config, options);
  const replay::ReplayResult result =
      replay_and_report(std::move(options), out, report, args.has("viewer"));
  for (const std::string& w : result.reader.warnings)
    std::cerr << "mote replay: warning: " << w << '\n';
  if (!args.has("quiet")) {
    replay::print_summary(std::cout, result, report);
    std::cout << "  outputs               " << out.string() << '\n';
  }
  return warn_unless_localized("replay", result);
}

}  // namespace mote::tool
