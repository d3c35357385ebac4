// The mote executable: help, exit statuses (0 ok, 2 bad usage, 1 bad input), one-line errors
// naming the file, and end-to-end replays (simulated log; Intel log when the data is present).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "mote_test/data.hpp"

namespace mote_cli_test {
namespace {

fs::path floorplan() { return fs::path(MOTE_SOURCE_DIR) / "sim/data/floorplan.yaml"; }

/// Simulates `seconds` of the floor plan into dir (sim.clf, sim.gt.tum).
void simulate_floorplan(const fs::path& dir, int seconds, int seed) {
  const Outcome sim =
      mote("simulate --map '" + floorplan().string() + "' --out '" + dir.string() + "' --seconds " +
           std::to_string(seconds) + " --seed " + std::to_string(seed));
  ASSERT_EQ(sim.status, 0) << sim.err;
}

/// A replay of a log of the floor plan against its ground truth.
std::string replay_floorplan(const fs::path& log, const fs::path& reference, const fs::path& out) {
  return "replay --map '" + floorplan().string() + "' --log '" + log.string() + "' --reference '" +
         reference.string() + "' --out '" + out.string() + "'";
}

/// A replay of dir's simulated log, writing to dir/out.
std::string replay_simulated(const fs::path& dir) {
  return replay_floorplan(dir / "sim.clf", dir / "sim.gt.tum", dir / "out");
}

/// Replays dir's simulated log with the beam model, 1000 particles and `yaml` as its config;
/// returns report.json (empty, the failure reported, when the replay fails).
std::string replay_beam_report(const fs::path& dir, const std::string& yaml) {
  std::ofstream(dir / "config.yaml") << yaml;
  fs::remove_all(dir / "out");
  const Outcome o =
      mote(replay_simulated(dir) + " --particles 1000 --model beam --quiet --config '" +
           (dir / "config.yaml").string() + "'");
  EXPECT_EQ(o.status, 0) << o.err;
  return o.status == 0 ? slurp(dir / "out" / "report.json") : std::string();
}

TEST(Cli, HelpDocumentsEveryCommandAndFlag) {
  const Outcome top = mote("--help");
  EXPECT_EQ(top.status, 0);
  for (const char* cmd : {"replay", "simulate", "kidnap", "crowd", "run", "info"})
    EXPECT_NE(top.out.find(cmd), std::string::npos);
  const Outcome replay = mote("replay --help");
  EXPECT_EQ(replay.status, 0);
  for (const char* flag : {"--map",
                           "--log",
                           "--out",
                           "--reference",
                           "--config",
                           "--model",
                           "--particles",
                           "--min-particles",
                           "--max-particles",
                           "--beams",
                           "--threads",
                           "--seed",
                           "--init",
                           "--init-pose",
                           "--lenient",
                           "--kidnapped-at",
                           "--laser-max-range",
                           "--scan-topic",
                           "--odom-topic",
                           "--odom-frame",
                           "--base-frame"}) {
    EXPECT_NE(replay.out.find(flag), std::string::npos) << flag;
  }
  EXPECT_EQ(mote("info --help").status, 0);
  EXPECT_EQ(mote("simulate --help").status, 0);
  EXPECT_EQ(mote("run --help").status, 0);
  const Outcome kidnap = mote("kidnap --help");
  EXPECT_EQ(kidnap.status, 0);
  for (const char* flag : {"--log", "--reference", "--out", "--keep-first", "--keep-last"}) {
    EXPECT_NE(kidnap.out.find(flag), std::string::npos) << flag;
  }
}

TEST(Cli, BadUsageExitsWithTwoAndOneLine) {
  for (const char* args :
       {"", "frobnicate", "replay --bogus 1", "replay --map", "replay --map m.yaml --log l.clf",
        "replay --map m.yaml --log l.clf --out d --particles ten",
        "replay --map m.yaml --log l.clf --out d --threads -1",
        "replay --map m.yaml --log l.clf --out d --model sonar",
        "replay --map m.yaml --log l.clf --out d --init-pose 1,2",
        "simulate --map m.yaml --out d --seconds 1e999", "run --seed x", "info",
        "info log.mcap --bogus"}) {
    const Outcome o = mote(args);
    EXPECT_EQ(o.status, 2) << args;
    if (std::string(args).empty()) continue;  // no command: the help text goes to stderr
    EXPECT_EQ(lines(o.err), 1) << args << ": " << o.err;
  }
}

TEST(Cli, AMisspelledFlagGetsTheFlagItMeant) {
  const Outcome typo = mote("replay --map m.yaml --log l.clf --out d --partciles 500");
  EXPECT_EQ(typo.status, 2);
  EXPECT_NE(typo.err.find("unknown flag '--partciles' (did you mean '--particles'?)"),
            std::string::npos)
      << typo.err;
  const Outcome unrelated = mote("replay --map m.yaml --log l.clf --out d --frobnicate 1");
  EXPECT_EQ(unrelated.status, 2);
  EXPECT_EQ(unrelated.err.find("did you mean"), std::string::npos) << unrelated.err;
}

TEST(Cli, AMisspelledCommandGetsTheCommandItMeant) {
  const Outcome typo = mote("replya --map m.yaml");
  EXPECT_EQ(typo.status, 2);
  EXPECT_NE(typo.err.find("unknown command 'replya' (did you mean 'mote replay'?)"),
            std::string::npos)
      << typo.err;
  const Outcome unrelated = mote("frobnicate");
  EXPECT_EQ(unrelated.status, 2);
  EXPECT_EQ(unrelated.err.find("did you mean"), std::string::npos) << unrelated.err;
}

TEST(Cli, BadInputExitsWithOneNamingTheFile) {
  const fs::path dir = scratch("bad_input");
  const fs::path yaml = dir / "broken.yaml";
  std::ofstream(yaml) << "image: missing.pgm\nresolution: -1\n";
  const Outcome o = mote("replay --map '" + yaml.string() + "' --log x.clf --out '" +
                         (dir / "out").string() + "'");
  EXPECT_EQ(o.status, 1);
  EXPECT_EQ(lines(o.err), 1) << o.err;
  EXPECT_NE(o.err.find("broken.yaml"), std::string::npos) << o.err;
}

TEST(Cli, SimulateThenReplayWritesTheOutputs) {
  const fs::path dir = scratch("sim");
  ASSERT_NO_FATAL_FAILURE(simulate_floorplan(dir, 15, 3));
  const Outcome o = mote(replay_simulated(dir) + " --particles 2000 --profile");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.out.find("ATE RMSE"), std::string::npos);
  EXPECT_NE(o.out.find("ns/particle"), std::string::npos);  // the --profile phase table
  EXPECT_NE(slurp(dir / "out" / "profile.folded").find("mote;update;sensor "), std::string::npos);
  const std::string report = slurp(dir / "out" / "report.json");
  EXPECT_DOUBLE_EQ(json_number(report, "particles_mean"), 2000.0);
  EXPECT_LT(json_number(report, "ate_rmse_m"), 0.2);
  EXPECT_TRUE(fs::exists(dir / "out" / "map.png"));
  EXPECT_TRUE(fs::exists(dir / "out" / "trajectory.tum"));
  EXPECT_EQ(report.find("nan"), std::string::npos);
}

// The demo writes the viewer page when asked, as mote replay does (it refused the flag).
TEST(Cli, RunWithViewerWritesThePage) {
  const fs::path dir = scratch("run_viewer");
  const Outcome o = mote("run --seconds 10 --out '" + dir.string() + "' --viewer");
  ASSERT_EQ(o.status, 0) << o.err;
  const std::string page = slurp(dir / "viewer.html");
  EXPECT_NE(page.find("<script id=\"mote-data\""), std::string::npos);
  EXPECT_NE(page.find("\"total_ms\":["), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "map.png"));
}

// A simulated log spliced by mote kidnap, replayed with --kidnapped-at: the report says whether
// and when the filter recovered, and the laser range it used (recorded by ROBOTLASER1).
TEST(Cli, KidnapThenReplayReportsRecovery) {
  const fs::path dir = scratch("kidnap");
  ASSERT_NO_FATAL_FAILURE(simulate_floorplan(dir, 20, 4));
  const Outcome k = mote("kidnap --log '" + (dir / "sim.clf").string() + "' --reference '" +
                         (dir / "sim.gt.tum").string() + "' --out '" + (dir / "k").string() + "'");
  ASSERT_EQ(k.status, 0) << k.err;
  const auto at = k.out.find("splice stamp ");
  ASSERT_NE(at, std::string::npos) << k.out;
  const std::string stamp = k.out.substr(at + 13, k.out.find('\n', at) - at - 13);
  const Outcome o =
      mote(replay_floorplan(dir / "k" / "kidnap.clf", dir / "k" / "kidnap.tum", dir / "out") +
           " --particles 1000 --kidnapped-at " + stamp);
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.out.find("recover"), std::string::npos) << o.out;
  const std::string report = slurp(dir / "out" / "report.json");
  EXPECT_NE(report.find("\"recovered_after_updates\""), std::string::npos);
  EXPECT_NE(report.find("ROBOTLASER1"), std::string::npos);
  // Without a reference there is nothing to recover to.
  EXPECT_EQ(mote("replay --map m.yaml --log l.clf --out d --kidnapped-at 3").status, 2);
}

// The ROS 2 recording (TurtleBot 4, issue 16) in its four containers.
const std::array<const char*, 4> kRos2Containers{"ros2/mac_take2", "ros2/mac_take2_zstd.mcap",
                                                 "ros2/mac_take2_lz4.mcap",
                                                 "ros2/mac_take2_uncompressed.mcap"};

// The rosbag2 folder (sqlite3) and the three MCAP files hold the same messages, so replaying
// them must give byte-identical trajectories; 357 scans, none skipped, no warning.
TEST(Cli, Ros2ContainersReplayToIdenticalTrajectories) {
  MOTE_REQUIRE_DATA(yaml, "ros2/mac_1st_floor_9_23.yaml");
  const fs::path dir = scratch("ros2_containers");
  std::string first;
  for (const char* container : kRos2Containers) {
    const fs::path out = dir / fs::path(container).filename();
    const Outcome o = mote("replay --map '" + yaml.string() + "' --log '" +
                           (mote::test::data_dir() / container).string() + "' --out '" +
                           out.string() + "' --quiet --seed 1");
    ASSERT_EQ(o.status, 0) << container << ": " << o.err;
    EXPECT_EQ(o.err, "") << container;
    const std::string report = slurp(out / "report.json");
    EXPECT_DOUBLE_EQ(json_number(report, "scans"), 357.0) << container;
    EXPECT_DOUBLE_EQ(json_number(report, "records_skipped"), 0.0) << container;
    const std::string tum = slurp(out / "trajectory.tum");
    EXPECT_GT(lines(tum), 20) << container;
    if (first.empty()) first = tum;
    EXPECT_EQ(tum, first) << container << " differs from " << kRos2Containers[0];
  }
}

// `mote info` on the MCAP file and the CARMEN log: storage, counts per topic, the laser.
TEST(Cli, InfoDescribesRos2AndCarmenLogs) {
  MOTE_REQUIRE_DATA(mcap, "ros2/mac_take2_zstd.mcap");
  const Outcome o = mote("info '" + mcap.string() + "'");
  ASSERT_EQ(o.status, 0) << o.err;
  for (const char* text :
       {"mcap, summary and chunk index", "compression       zstd", "duration          46.203 s",
        "messages          2232", "/scan                        357  sensor_msgs/msg/LaserScan",
        "/odom                        920  nav_msgs/msg/Odometry", "beams             720",
        "359.50 deg", "0.150 to 12.000 m", "yaw 90.00 deg", "base_link -> rplidar_link (static)",
        "odom -> base_link"}) {
    EXPECT_NE(o.out.find(text), std::string::npos) << text << " in\n" << o.out;
  }
  MOTE_REQUIRE_DATA(clf, "intel/intel.clf");
  const Outcome c = mote("info '" + clf.string() + "'");
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(c.out.find("FLASER                       910"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("beams             180"), std::string::npos) << c.out;
  const Outcome bad = mote("info '" + (fs::path(MOTE_SOURCE_DIR) / "README.md").string() + "'");
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(lines(bad.err), 1) << bad.err;
}

// Issue 19: `mote info --map` builds the range table and prints its layout, memory, build time
// and error against Embree; a budget too small for any table is a one-line error naming the
// size needed.
TEST(Cli, InfoMapReportsTheRangeTable) {
  const Outcome o = mote("info --map '" + floorplan().string() + "' --range-table-angles 64");
  ASSERT_EQ(o.status, 0) << o.err;
  for (const char* text : {"range table           64 angles, lattice 1", "memory", "build",
                           "% within 1 cell", "error (cells)"}) {
    EXPECT_NE(o.out.find(text), std::string::npos) << text << " in\n" << o.out;
  }
  // 12.5 MB on every cell at 64 angles: at 3 MB the table is on a coarser lattice.
  const Outcome coarse = mote("info --map '" + floorplan().string() +
                              "' --range-table-angles 64 --range-table-budget-mb 3");
  ASSERT_EQ(coarse.status, 0) << coarse.err;
  EXPECT_NE(coarse.out.find("64 angles, lattice "), std::string::npos) << coarse.out;
  EXPECT_EQ(coarse.out.find("64 angles, lattice 1 "), std::string::npos) << coarse.out;
  EXPECT_NE(coarse.out.find("% within 1 cell"), std::string::npos) << coarse.out;
  // Where no lattice fits, or only one coarser than sqrt(2) sigma_hit, the beam model casts
  // exactly: no table is built, and the output says why.
  const Outcome tiny =
      mote("info --map '" + floorplan().string() + "' --range-table-budget-mb 0.001");
  EXPECT_EQ(tiny.status, 0) << tiny.err;
  EXPECT_NE(tiny.out.find("ray casting           exact: no lattice of the range table fits"),
            std::string::npos)
      << tiny.out;
  const Outcome narrow =
      mote("info --map '" + floorplan().string() +
           "' --range-table-angles 64 --range-table-budget-mb 3 --sigma-hit 0.01");
  EXPECT_EQ(narrow.status, 0) << narrow.err;
  EXPECT_NE(narrow.out.find("coarser than sqrt(2) sigma_hit (0.01 m)"), std::string::npos)
      << narrow.out;
  EXPECT_EQ(narrow.out.find("% within 1 cell"), std::string::npos) << narrow.out;
  // Unknown cells open to rays by default, as the beam model runs; --unknown-blocks as nav2's.
  const Outcome blocks =
      mote("info --map '" + floorplan().string() + "' --range-table-angles 64 --unknown-blocks");
  EXPECT_EQ(blocks.status, 0) << blocks.err;
  EXPECT_NE(blocks.out.find("64 angles, lattice 1"), std::string::npos) << blocks.out;
}

// Issue 19: a table over budget is built on a coarser lattice, report.json says which, and the
// coarser table tracks a simulated log.
TEST(Cli, ReplayReportsTheCoarserLatticeOfATableOverBudget) {
  const fs::path dir = scratch("coarse");
  ASSERT_NO_FATAL_FAILURE(simulate_floorplan(dir, 15, 3));
  // 12.5 MB on every cell at 64 angles (InfoMapReportsTheRangeTable).
  const std::string report = replay_beam_report(
      dir, "ray_casting: table\nrange_table_angles: 64\nrange_table_budget_mb: 3\n");
  EXPECT_GT(json_number(report, "lattice_cells"), 1.0) << report;
  EXPECT_LE(json_number(report, "lattice_cells"), json_number(report, "max_lattice_cells"));
  EXPECT_LT(json_number(report, "ate_rmse_m"), 0.2);
}

// Where the budget holds the table only on a lattice coarser than sqrt(2) sigma_hit (a big map),
// the beam model casts exactly, and the summary and report.json say why.
TEST(Cli, ReplayCastsExactlyWhereTheTableWouldBeCoarserThanSigmaHit) {
  const fs::path dir = scratch("coarser_than_sigma");
  ASSERT_NO_FATAL_FAILURE(simulate_floorplan(dir, 15, 3));
  const std::string config =
      "ray_casting: table\nrange_table_angles: 64\nrange_table_budget_mb: 0.3\nsigma_hit: 0.1\n";
  const std::string report = replay_beam_report(dir, config);
  EXPECT_EQ(report.find("\"range_table\""), std::string::npos) << report;
  EXPECT_NE(report.find("\"table\": false"), std::string::npos) << report;
  EXPECT_GT(json_number(report, "budget_lattice_cells"), json_number(report, "max_lattice_cells"));
  EXPECT_LT(json_number(report, "ate_rmse_m"), 0.2);
  const Outcome o = mote(replay_simulated(dir) + " --particles 1000 --model beam --config '" +
                         (dir / "config.yaml").string() + "'");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(
      o.out.find("ray casting           exact: the range table fits 0.3 MB only on a lattice of "),
      std::string::npos)
      << o.out;
}

// An MCAP file cut short (here: the recording's zstd file cut in its middle, as a crash while
// recording leaves it) replays up to its last complete chunk, with one warning on stderr.
TEST(Cli, CutMcapReplaysWithAWarning) {
  MOTE_REQUIRE_DATA(yaml, "ros2/mac_1st_floor_9_23.yaml");
  const fs::path dir = scratch("ros2_cut");
  const std::string whole = slurp(yaml.parent_path() / "mac_take2_zstd.mcap");
  std::ofstream(dir / "cut.mcap", std::ios::binary) << whole.substr(0, whole.size() / 2);
  const Outcome o =
      mote("replay --map '" + yaml.string() + "' --log '" + (dir / "cut.mcap").string() +
           "' --out '" + (dir / "out").string() + "' --quiet --seed 1");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_EQ(lines(o.err), 1) << o.err;
  EXPECT_NE(o.err.find("mote replay: warning: " + (dir / "cut.mcap").string() + ": byte "),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("cut short while recording"), std::string::npos) << o.err;
  const double scans = json_number(slurp(dir / "out" / "report.json"), "scans");
  EXPECT_GT(scans, 100.0);
  EXPECT_LT(scans, 357.0);
}

// Issue 48: an --out that names a file failed only after the whole replay (or calibration). It
// is checked first now: here the map and log do not exist, and the error is about --out.
TEST(Cli, OutNamingAFileFailsBeforeTheReplay) {
  const fs::path dir = scratch("out_file");
  const fs::path file = dir / "taken.txt";
  std::ofstream(file) << "not a folder\n";
  for (const std::string command : {"replay", "calibrate"}) {
    const Outcome o = mote(command + " --map '" + (dir / "none.yaml").string() + "' --log '" +
                           (dir / "none.clf").string() + "' --out '" + file.string() + "'");
    EXPECT_EQ(o.status, 1) << command << ": " << o.err;
    EXPECT_EQ(lines(o.err), 1) << o.err;
    EXPECT_NE(o.err.find("mote " + command + ": " + file.string() +
                         ": the output folder is a file; name a folder (created if missing)"),
              std::string::npos)
        << o.err;
  }
  EXPECT_EQ(slurp(file), "not a folder\n");
}

// Issue 48: a .clf cut inside a line stops with exit status 1 and says it may be cut short and
// that --lenient reads what is there; with --lenient the replay runs to the cut.
TEST(Cli, CutCarmenLogNamesLenient) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const fs::path dir = scratch("intel_cut");
  const std::string whole = slurp(yaml.parent_path() / "intel.clf");
  std::ofstream(dir / "cut.clf", std::ios::binary) << whole.substr(0, whole.size() / 4 + 7);
  const std::string common = "replay --map '" + yaml.string() + "' --log '" +
                             (dir / "cut.clf").string() + "' --quiet --out '";
  const Outcome strict = mote(common + (dir / "strict").string() + "'");
  EXPECT_EQ(strict.status, 1) << strict.err;
  EXPECT_EQ(lines(strict.err), 1) << strict.err;
  EXPECT_NE(strict.err.find("mote replay: " + (dir / "cut.clf").string() + ": line "),
            std::string::npos)
      << strict.err;
  EXPECT_NE(strict.err.find("cut short? --lenient reads the "), std::string::npos) << strict.err;
  const Outcome lenient = mote(common + (dir / "lenient").string() + "' --lenient");
  EXPECT_EQ(lenient.status, 0) << lenient.err;
  const double scans = json_number(slurp(dir / "lenient" / "report.json"), "scans");
  EXPECT_GT(scans, 100.0);
  EXPECT_LT(scans, 910.0);
}

}  // namespace
}  // namespace mote_cli_test
