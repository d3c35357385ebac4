// The mote tool on the shared recorded logs: accuracy with the shipped config and with the
// defaults (issue 15's targets), global localization seeds, kidnapping and crowd recovery.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "mote_test/data.hpp"

namespace mote_cli_test {
namespace {

// `mote replay --init global` of `log` on `yaml` with `seed` (and `flags`) into `out`.
Outcome replay_global(const fs::path& yaml, const fs::path& log, const fs::path& out, int seed,
                      const std::string& flags = "") {
  return mote("replay --map '" + yaml.string() + "' --log '" + log.string() + "' --out '" +
              out.string() + "' --init global --quiet --seed " + std::to_string(seed) + flags);
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
    const Outcome o = replay_global(yaml, yaml.parent_path() / "dis-underground.bag", out, seed);
    ASSERT_EQ(o.status, 0) << o.err;
    const std::string report = slurp(out / "report.json");
    EXPECT_DOUBLE_EQ(json_number(report, "scans"), 4427.0);
    EXPECT_DOUBLE_EQ(json_number(report, "records_skipped"), 0.0);
    EXPECT_GT(json_number(report, "updates"), 100.0);
    const std::array<double, 2> xy = end_position(out);
    ends.push_back(xy);
  }
  expect_within(ends, 0.3);
}

// Issue 15: global localization on the Wean Hall log (a corridor whose doors look alike)
// with mote's defaults ends in the doorway of the cluttered room at the corridor's south end
// where the robot drove (map.png), at (41.45, 40.28): seeds 1-5 all end there, within 0.3 m of
// each other. (With six particles per KLD bin none of seeds 1-120 missed it, nor of 1-40 under
// MOTE_ISA=generic and avx2; at two per bin capped at 100000, 8 of 120 took a look-alike door.)
TEST(Cli, WeanGlobalLocalizationSeedsAgree) {
  MOTE_REQUIRE_DATA(yaml, "wean/wean_map.yaml");
  const fs::path dir = scratch("wean");
  std::vector<std::array<double, 2>> ends;
  for (int seed = 1; seed <= 5; ++seed) {
    const fs::path out = dir / ("seed" + std::to_string(seed));
    const Outcome o = replay_global(yaml, yaml.parent_path() / "robotdata1.clf", out, seed);
    ASSERT_EQ(o.status, 0) << o.err;
    const std::string report = slurp(out / "report.json");
    EXPECT_DOUBLE_EQ(json_number(report, "scans"), 713.0);
    EXPECT_DOUBLE_EQ(json_number(report, "records_skipped"), 0.0);
    // One place once the global search has settled: `uncertain` only around its first updates
    // (2.4-5.3 % of the updates on seeds 1-5). A corridor's look-alike stretch 5 m along that no
    // reading tells apart, kept as a second place while the likelihood kept refusing it, made it
    // 13-14 % (the fallen place's evidence as one scan's McNemar test alone).
    EXPECT_LE(json_number(report, "uncertain"), 0.10) << "seed " << seed;
    const std::array<double, 2> xy = end_position(out);
    ASSERT_FALSE(std::isnan(xy[0])) << "seed " << seed << ": no end pose";
    EXPECT_LT(std::hypot(xy[0] - 41.45, xy[1] - 40.28), 0.5)
        << "seed " << seed << " ends at (" << xy[0] << ", " << xy[1] << ")";
    ends.push_back(xy);
  }
  expect_within(ends, 0.3);
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

// The beam model with the range table (the default) tracks Intel within 5% of the exact beam
// model's ATE (same defaults, seed and particles; `ray_casting: exact` changes only where the
// expected ranges come from), and report.json says what the table cost.
TEST(Cli, IntelBeamModelWithTheRangeTableTracksAsExactCasting) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const fs::path data = yaml.parent_path();
  const fs::path exact_yaml = scratch("intel-beam-exact-config") / "exact.yaml";
  std::ofstream(exact_yaml) << "ray_casting: exact\n";
  std::array<double, 2> ate{};
  for (const bool table : {false, true}) {
    const fs::path out = scratch(table ? "intel-beam-table" : "intel-beam-exact");
    const std::string config = table ? std::string() : " --config '" + exact_yaml.string() + "'";
    const Outcome o =
        mote("replay --map '" + yaml.string() + "' --log '" + (data / "intel.clf").string() +
             "' --reference '" + (data / "intel.gt.tum").string() +
             "' --particles 5000 --model beam --quiet" + config + " --out '" + out.string() + "'");
    ASSERT_EQ(o.status, 0) << o.err;
    const std::string report = slurp(out / "report.json");
    ate[table ? 1 : 0] = json_number(report, "ate_rmse_m");
    EXPECT_EQ(report.find("\"range_table\"") != std::string::npos, table);
    if (table) {
      // The table's accuracy floors are RangeTable.*CloseToEmbree's (rays stopped by unknown
      // cells); here rays cross unknown cells (the default), which lengthens them and leaves
      // 87 % within a cell on Intel: the report must carry the share, the ATE below judges it.
      const double within = json_number(report, "within_one_cell");
      EXPECT_GT(within, 0.0);
      EXPECT_LE(within, 1.0);
      EXPECT_LE(json_number(report, "bytes"), 256.0 * 1048576.0);
    }
  }
  EXPECT_LE(ate[1], 1.05 * ate[0]) << "exact " << ate[0] << " m, table " << ate[1] << " m";
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
  // Carried 27 m: every re-localization that settled found the robot there, none stayed put.
  EXPECT_GE(json_number(report, "relocalizations_moved_pose"), 1.0) << report;
}

// A ring of eight people (mote crowd: 0.4-1.0 m from the robot) around it for the 20 s of the
// Intel log that turn the most on the spot, blocking 78% of those scans' beams. With mote's
// defaults the likelihood field rides it out within the goal for unseen logs (0.10 m); with
// unmapped_obstacle_filter (and the re-localization that would find it again) off, the crowd
// carries it metres away. Measured: ATE 0.093 m (max 0.94 m) against a max error of 3.3 m.
TEST(Cli, IntelCrowdIsRiddenOutWithTheDefaults) {
  MOTE_REQUIRE_DATA(yaml, "intel/intel.yaml");
  const fs::path data = yaml.parent_path();
  const fs::path dir = scratch("intel-crowd");
  const Outcome made =
      mote("crowd --log '" + (data / "intel.clf").string() + "' --out '" + dir.string() + "'");
  ASSERT_EQ(made.status, 0) << made.err;
  {
    std::ofstream off(dir / "off.yaml");
    off << "unmapped_obstacle_filter: false\nrelocalize_when_lost: false\n";
  }
  const auto report = [&](const std::string& extra, const std::string& name) {
    const Outcome o =
        mote("replay --map '" + yaml.string() + "' --log '" + (dir / "crowd.clf").string() +
             "' --reference '" + (data / "intel.gt.tum").string() +
             "' --particles 5000 --quiet --out '" + (dir / name).string() + "'" + extra);
    // Without the filter the run may end lost (status 3); with the defaults it ends localized.
    EXPECT_TRUE(o.status == 0 || (!extra.empty() && o.status == 3)) << o.status << o.err;
    return slurp(dir / name / "report.json");
  };
  EXPECT_LE(json_number(report("", "on"), "ate_rmse_m"), 0.10);
  EXPECT_GT(
      json_number(report(" --config '" + (dir / "off.yaml").string() + "'", "off"), "max_error_m"),
      2.0);
}

// Issue 16: global localization on the MAC first floor map with 20000 particles ends at the
// same place for seeds 1-5 (within 0.3 m); issue 15: so does it with mote's defaults (no
// particle count). Measured: within 0.01 m and 0.02 m, at (8.11, -14.66), in the corridor the
// robot drove down (map.png).
void expect_ros2_seeds_agree(const std::string& flags, const std::string& name) {
  MOTE_REQUIRE_DATA(yaml, "ros2/mac_1st_floor_9_23.yaml");
  const fs::path dir = scratch(name);
  std::vector<std::array<double, 2>> ends;
  for (const int seed : {1, 2, 3, 4, 5}) {
    const fs::path out = dir / ("seed" + std::to_string(seed));
    const Outcome o =
        replay_global(yaml, yaml.parent_path() / "mac_take2_zstd.mcap", out, seed, flags);
    ASSERT_EQ(o.status, 0) << o.err;
    ends.push_back(end_position(out));
  }
  expect_within(ends, 0.3);
  EXPECT_LT(std::hypot(ends[0][0] - 8.11, ends[0][1] + 14.66), 0.5);
}

TEST(Cli, Ros2GlobalLocalizationSeedsAgree) {
  expect_ros2_seeds_agree(" --particles 20000", "ros2_global");
}

TEST(Cli, Ros2GlobalLocalizationSeedsAgreeWithTheDefaults) {
  expect_ros2_seeds_agree("", "ros2_global_defaults");
}

}  // namespace
}  // namespace mote_cli_test
