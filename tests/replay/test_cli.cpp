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

#include "mote_test/data.hpp"

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A folder of this process's own: ctest runs each test in its own process, in parallel.
fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("mote_test_cli_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs `mote ARGS` through the shell, stdout captured by popen and stderr through a file.
Outcome mote(const std::string& args) {
  const fs::path err = scratch("stderr") / "err.txt";
  const std::string cmd = std::string("'") + MOTE_EXE + "' " + args + " 2>'" + err.string() + "'";
  Outcome o;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return o;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe) != nullptr) o.out += buf.data();
  const int raw = pclose(pipe);
  o.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  o.err = slurp(err);
  return o;
}

// The number after "key": in a report.json; NaN when absent or null.
double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + key.size() + 4, nullptr);
}

int lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// The last non-empty line of text.
std::string last_line(const std::string& text) {
  const std::size_t end = text.find_last_not_of('\n');
  if (end == std::string::npos) return "";
  const std::size_t start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1, end - start);
}

TEST(Cli, HelpDocumentsEveryCommandAndFlag) {
  const Outcome top = mote("--help");
  EXPECT_EQ(top.status, 0);
  for (const char* cmd : {"replay", "simulate", "kidnap", "run", "info"})
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
  const fs::path map = fs::path(MOTE_SOURCE_DIR) / "replay/data/floorplan.yaml";
  ASSERT_EQ(mote("simulate --map '" + map.string() + "' --out '" + dir.string() +
                 "' --seconds 15 --seed 3")
                .status,
            0);
  const Outcome o =
      mote("replay --map '" + map.string() + "' --log '" + (dir / "sim.clf").string() +
           "' --reference '" + (dir / "sim.gt.tum").string() + "' --out '" +
           (dir / "out").string() + "' --particles 2000 --profile");
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

// A simulated log spliced by mote kidnap, replayed with --kidnapped-at: the report says whether
// and when the filter recovered, and the laser range it used (recorded by ROBOTLASER1).
TEST(Cli, KidnapThenReplayReportsRecovery) {
  const fs::path dir = scratch("kidnap");
  const fs::path map = fs::path(MOTE_SOURCE_DIR) / "replay/data/floorplan.yaml";
  ASSERT_EQ(mote("simulate --map '" + map.string() + "' --out '" + dir.string() +
                 "' --seconds 20 --seed 4")
                .status,
            0);
  const Outcome k = mote("kidnap --log '" + (dir / "sim.clf").string() + "' --reference '" +
                         (dir / "sim.gt.tum").string() + "' --out '" + (dir / "k").string() + "'");
  ASSERT_EQ(k.status, 0) << k.err;
  const auto at = k.out.find("splice stamp ");
  ASSERT_NE(at, std::string::npos) << k.out;
  const std::string stamp = k.out.substr(at + 13, k.out.find('\n', at) - at - 13);
  const Outcome o =
      mote("replay --map '" + map.string() + "' --log '" + (dir / "k" / "kidnap.clf").string() +
           "' --reference '" + (dir / "k" / "kidnap.tum").string() + "' --out '" +
           (dir / "out").string() + "' --particles 1000 --kidnapped-at " + stamp);
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.out.find("recover"), std::string::npos) << o.out;
  const std::string report = slurp(dir / "out" / "report.json");
  EXPECT_NE(report.find("\"recovered_after_updates\""), std::string::npos);
  EXPECT_NE(report.find("ROBOTLASER1"), std::string::npos);
  // Without a reference there is nothing to recover to.
  EXPECT_EQ(mote("replay --map m.yaml --log l.clf --out d --kidnapped-at 3").status, 2);
}

// Accuracy on the Intel lab log with the configuration the project ships for it
// (replay/configs/intel.yaml explains each value), and bit-identical trajectories on 1 and 2
// threads (design.md section 3, determinism).
TEST(Cli, IntelReplayAccuracyAndThreadInvariance) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const fs::path data = yaml.parent_path();
  const fs::path dir = scratch("intel");
  const fs::path config = fs::path(MOTE_SOURCE_DIR) / "replay/configs/intel.yaml";
  const std::string common = "replay --map '" + yaml.string() + "' --log '" +
                             (data / "intel.clf").string() + "' --reference '" +
                             (data / "intel.gt.tum").string() + "' --config '" + config.string() +
                             "' --particles 5000 --model likelihood_field --quiet";
  ASSERT_EQ(mote(common + " --threads 1 --out '" + (dir / "t1").string() + "'").status, 0);
  ASSERT_EQ(mote(common + " --threads 2 --out '" + (dir / "t2").string() + "'").status, 0);
  const std::string t1 = slurp(dir / "t1" / "trajectory.tum");
  EXPECT_GT(lines(t1), 800);
  EXPECT_EQ(t1, slurp(dir / "t2" / "trajectory.tum"));
  const std::string report = slurp(dir / "t2" / "report.json");
  // Issue 6: ATE RMSE at most 0.05 m, heading RMSE at most 1 degree.
  EXPECT_LE(json_number(report, "ate_rmse_m"), 0.05);
  EXPECT_LE(json_number(report, "heading_rmse_deg"), 1.0);
}

// Every pair of end positions within `bound` metres.
void expect_within(const std::vector<std::array<double, 2>>& ends, double bound) {
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (std::size_t j = i + 1; j < ends.size(); ++j) {
      EXPECT_LT(std::hypot(ends[i][0] - ends[j][0], ends[i][1] - ends[j][1]), bound)
          << "seeds " << i + 1 << " and " << j + 1 << " end at (" << ends[i][0] << ", "
          << ends[i][1] << ") and (" << ends[j][0] << ", " << ends[j][1] << ")";
    }
  }
}

// The Sapienza DIS bag (ROS 1, LaserScan + Odometry + tf) replays to its last scan, and global
// localization with mote's defaults (no config, no particle count) from seeds 1-5 ends at the
// same place (issue 15: within 0.3 m): a bag read wrongly (frames, stamps, mounting transform)
// would not localize consistently. Measured: within 0.01 m.
TEST(Cli, DisBagReplaysToTheEndAndSeedsAgree) {
  MOTE_REQUIRE_DATA(yaml, "dis/dis_underground.yaml");
  const fs::path dir = scratch("dis");
  std::vector<std::array<double, 2>> ends;
  for (const int seed : {1, 2, 3, 4, 5}) {
    const fs::path out = dir / ("seed" + std::to_string(seed));
    const Outcome o = mote("replay --map '" + yaml.string() + "' --log '" +
                           (yaml.parent_path() / "dis-underground.bag").string() + "' --out '" +
                           out.string() + "' --init global --quiet --seed " + std::to_string(seed));
    ASSERT_EQ(o.status, 0) << o.err;
    const std::string report = slurp(out / "report.json");
    EXPECT_DOUBLE_EQ(json_number(report, "scans"), 4427.0);
    EXPECT_DOUBLE_EQ(json_number(report, "records_skipped"), 0.0);
    EXPECT_GT(json_number(report, "updates"), 100.0);
    std::istringstream last(last_line(slurp(out / "trajectory.tum")));
    double stamp = 0.0;
    std::array<double, 2> xy{};
    last >> stamp >> xy[0] >> xy[1];
    ends.push_back(xy);
  }
  expect_within(ends, 0.3);
}

// Issue 15: global localization on the Wean Hall log (a corridor whose doors look alike)
// with mote's defaults ends in the doorway of the cluttered room at the corridor's south end
// where the robot drove (map.png), at (41.45, 40.28). A seed sometimes takes a look-alike door
// instead, and which seeds do changes with the last bits of the arithmetic: seeds 1-40 missed
// 2 times in 40 with MOTE_NATIVE, 2 with the portable build's avx2 variant and 4 with generic
// (seed 4 of 1-5 under avx2, none of 1-5 in the other two). So the test holds a rate, not a
// seed: at least 8 of seeds 1-10 end within 0.5 m of that place (a filter converging 95% of
// the time passes 99% of builds; one converging half the time fails 95%), and the seeds that do
// end there agree within 0.3 m.
TEST(Cli, WeanGlobalLocalizationSeedsAgree) {
  MOTE_REQUIRE_DATA(yaml, "wean/wean_map.yaml");
  const fs::path dir = scratch("wean");
  std::vector<std::array<double, 2>> at_the_door;
  for (int seed = 1; seed <= 10; ++seed) {
    const fs::path out = dir / ("seed" + std::to_string(seed));
    const Outcome o = mote("replay --map '" + yaml.string() + "' --log '" +
                           (yaml.parent_path() / "robotdata1.clf").string() + "' --out '" +
                           out.string() + "' --init global --quiet --seed " + std::to_string(seed));
    ASSERT_EQ(o.status, 0) << o.err;
    const std::string report = slurp(out / "report.json");
    EXPECT_DOUBLE_EQ(json_number(report, "scans"), 713.0);
    EXPECT_DOUBLE_EQ(json_number(report, "records_skipped"), 0.0);
    std::istringstream last(last_line(slurp(out / "trajectory.tum")));
    double stamp = 0.0;
    std::array<double, 2> xy{};
    last >> stamp >> xy[0] >> xy[1];
    ASSERT_FALSE(last.fail()) << "seed " << seed << ": no end pose";
    if (std::hypot(xy[0] - 41.45, xy[1] - 40.28) < 0.5) {
      at_the_door.push_back(xy);
    } else {
      std::cout << "seed " << seed << " ends at (" << xy[0] << ", " << xy[1] << ")\n";
    }
  }
  EXPECT_GE(at_the_door.size(), 8U) << "of seeds 1-10 ended at (41.45, 40.28)";
  expect_within(at_the_door, 0.3);
}

// Issue 15: tracking on the Intel log with mote's defaults (no config), 5000 particles: the
// likelihood field within 0.06 m and 1 degree, the beam model within 0.08 m and 1.5 degrees.
void expect_intel_defaults(const std::string& model, double ate_m, double heading_deg) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const fs::path data = yaml.parent_path();
  const fs::path out = scratch("intel-defaults-" + model);
  const Outcome o =
      mote("replay --map '" + yaml.string() + "' --log '" + (data / "intel.clf").string() +
           "' --reference '" + (data / "intel.gt.tum").string() + "' --particles 5000 --model " +
           model + " --quiet --out '" + out.string() + "'");
  ASSERT_EQ(o.status, 0) << o.err;
  const std::string report = slurp(out / "report.json");
  EXPECT_LE(json_number(report, "ate_rmse_m"), ate_m);
  EXPECT_LE(json_number(report, "heading_rmse_deg"), heading_deg);
}

TEST(Cli, IntelDefaultsTrackWithTheLikelihoodField) {
  expect_intel_defaults("likelihood_field", 0.06, 1.0);
}

TEST(Cli, IntelDefaultsTrackWithTheBeamModel) { expect_intel_defaults("beam", 0.08, 1.5); }

// Issue 14: the kidnapping made from the Intel log (mote kidnap: first 40% and last 30% of the
// scans, the odometry continued smoothly, the robot carried 27 m), 5000 particles, mote's
// defaults: back within 0.3 m, and staying there for 20 updates, within 30 updates of the
// splice. Measured: 6 (nav2's defaults, recovery off: 95; before the recovery fixes: 94).
TEST(Cli, IntelKidnappingRecoversWithin30Updates) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const fs::path data = yaml.parent_path();
  const fs::path dir = scratch("intel-kidnap");
  const Outcome made = mote("kidnap --log '" + (data / "intel.clf").string() + "' --reference '" +
                            (data / "intel.gt.tum").string() + "' --out '" + dir.string() + "'");
  ASSERT_EQ(made.status, 0) << made.err;
  const std::size_t at = made.out.find("splice stamp ");
  ASSERT_NE(at, std::string::npos) << made.out;
  const std::string stamp = made.out.substr(at + 13, made.out.find('\n', at) - at - 13);
  const Outcome o = mote("replay --map '" + yaml.string() + "' --log '" +
                         (dir / "kidnap.clf").string() + "' --reference '" +
                         (dir / "kidnap.tum").string() + "' --particles 5000 --kidnapped-at " +
                         stamp + " --quiet --out '" + (dir / "out").string() + "'");
  ASSERT_EQ(o.status, 0) << o.err;
  const std::string report = slurp(dir / "out" / "report.json");
  ASSERT_NE(report.find("\"recovered\": true"), std::string::npos) << report;
  EXPECT_LE(json_number(report, "recovered_after_updates"), 30.0);
}

// Issue 15: a ring of eight people (mote crowd: 0.4-1.0 m from the robot) around it for the
// 20 s of the Intel log that turn the most on the spot, blocking 78% of those scans' beams.
// With mote's defaults the likelihood field rides it out within the goal for unseen logs
// (0.10 m); with unmapped_obstacle_filter off it is lost (measured 0.082 m against 1.72 m).
TEST(Cli, IntelCrowdIsRiddenOutWithTheDefaults) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const fs::path data = yaml.parent_path();
  const fs::path dir = scratch("intel-crowd");
  const Outcome made =
      mote("crowd --log '" + (data / "intel.clf").string() + "' --out '" + dir.string() + "'");
  ASSERT_EQ(made.status, 0) << made.err;
  {
    std::ofstream off(dir / "off.yaml");
    off << "unmapped_obstacle_filter: false\n";
  }
  const auto ate = [&](const std::string& extra, const std::string& name) {
    const Outcome o =
        mote("replay --map '" + yaml.string() + "' --log '" + (dir / "crowd.clf").string() +
             "' --reference '" + (data / "intel.gt.tum").string() +
             "' --particles 5000 --quiet --out '" + (dir / name).string() + "'" + extra);
    EXPECT_EQ(o.status, 0) << o.err;
    return json_number(slurp(dir / name / "report.json"), "ate_rmse_m");
  };
  EXPECT_LE(ate("", "on"), 0.10);
  EXPECT_GT(ate(" --config '" + (dir / "off.yaml").string() + "'", "off"), 0.5);
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

// Issue 16: global localization on the MAC first floor map with 20000 particles ends at the
// same place for seeds 1-5 (within 0.3 m). Measured: within 0.01 m, at
// (8.11, -14.66), in the corridor the robot drove down (map.png).
TEST(Cli, Ros2GlobalLocalizationSeedsAgree) {
  MOTE_REQUIRE_DATA(yaml, "ros2/mac_1st_floor_9_23.yaml");
  const fs::path dir = scratch("ros2_global");
  std::vector<std::array<double, 2>> ends;
  for (const int seed : {1, 2, 3, 4, 5}) {
    const fs::path out = dir / ("seed" + std::to_string(seed));
    const Outcome o =
        mote("replay --map '" + yaml.string() + "' --log '" +
             (yaml.parent_path() / "mac_take2_zstd.mcap").string() + "' --out '" + out.string() +
             "' --init global --particles 20000 --quiet --seed " + std::to_string(seed));
    ASSERT_EQ(o.status, 0) << o.err;
    std::istringstream last(last_line(slurp(out / "trajectory.tum")));
    double stamp = 0.0;
    std::array<double, 2> xy{};
    last >> stamp >> xy[0] >> xy[1];
    ends.push_back(xy);
  }
  expect_within(ends, 0.3);
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

}  // namespace
