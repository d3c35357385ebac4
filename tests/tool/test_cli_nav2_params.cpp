// `mote replay --config nav2_params.yaml` as a user who swaps amcl for mote runs it (issue 46):
// nav2's shipped file over mote's adaptive defaults tracks Intel from the true pose, where
// amcl's fixed behaviour (`--nav2-defaults`, or the file before issue 46) lost it on 94 % of the
// updates; the first lines printed say which defaults the run uses; the file's start pose
// applies.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_test_util.hpp"
#include "mote_test/data.hpp"

namespace mote_cli_test {
namespace {

// The nav2 params file as nav2_bringup ships it (tests/data/nav2_params.yaml).
fs::path nav2_file() { return fs::path(MOTE_SOURCE_DIR) / "tests" / "data" / "nav2_params.yaml"; }

std::string intel_args(const fs::path& intel, const fs::path& out) {
  return "replay --map '" + (intel / "intel.yaml").string() + "' --log '" +
         (intel / "intel.clf").string() + "' --out '" + out.string() + "'";
}

// The share of updates in `state`, from report.json's localization state.
double state_share(const std::string& report, const std::string& state) {
  const auto at = report.find("\"share\": {");
  if (at == std::string::npos) return std::nan("");
  return json_number(report.substr(at, report.find('}', at) - at), state);
}

// The same targets as a log mote has not seen with no flags (test_cli_no_flags.cpp): ATE within
// 0.10 m, no error above 1 m, no update lost.
TEST(CliNav2Params, ShippedFileTracksIntel) {
  MOTE_REQUIRE_DATA(intel, "intel");
  const fs::path out = scratch("nav2-params-intel");
  const Outcome o =
      mote(intel_args(intel, out) + " --reference '" + (intel / "intel.gt.tum").string() +
           "' --config '" + nav2_file().string() + "'");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  EXPECT_EQ(o.err, "") << "do_beamskip: false and nav2's frames ask for nothing";
  EXPECT_EQ(o.out.rfind("mote replay: defaults: mote's adaptive ones", 0), 0U) << o.out;
  EXPECT_NE(o.out.find("\nmote replay: config: " + nav2_file().string() + ", a nav2 params file"),
            std::string::npos)
      << o.out;
  const std::string report = slurp(out / "report.json");
  EXPECT_LE(json_number(report, "ate_rmse_m"), 0.10);
  EXPECT_LE(json_number(report, "max_error_m"), 1.0);
  EXPECT_DOUBLE_EQ(state_share(report, "lost"), 0.0);
  EXPECT_NE(report.find("\"max_particles\": 2000"), std::string::npos) << "the file's bound";
}

// --nav2-defaults with the file is amcl's behaviour under the file's values, and says so.
TEST(CliNav2Params, Nav2DefaultsWithTheFileAreAmclsBehaviour) {
  MOTE_REQUIRE_DATA(intel, "intel");
  const fs::path out = scratch("nav2-params-amcl");
  const Outcome o = mote(intel_args(intel, out) + " --config '" + nav2_file().string() +
                         "' --nav2-defaults --particles 500");
  ASSERT_NE(o.status, 1) << o.err;
  EXPECT_EQ(o.out.rfind("mote replay: defaults: nav2_amcl's fixed behaviour", 0), 0U) << o.out;
  EXPECT_NE(o.out.find("a nav2 params file over nav2_amcl's defaults"), std::string::npos);
  EXPECT_NE(o.out.find("tempering             fixed"), std::string::npos) << o.out;
  // The file naming mote's defaults and the flag nav2's is an error, not a silent choice.
  const fs::path file = out / "mote_defaults.yaml";
  std::ofstream(file) << "defaults: mote\n";
  const Outcome both =
      mote(intel_args(intel, out) + " --config '" + file.string() + "' --nav2-defaults");
  EXPECT_EQ(both.status, 1);
  EXPECT_NE(both.err.find("the file asks for mote's defaults, the caller for nav2's"),
            std::string::npos)
      << both.err;
}

// set_initial_pose and initial_pose start the run where the file says, with no reference: the
// run starts at Intel's first reference pose and ends at its last one.
TEST(CliNav2Params, InitialPoseFromTheFile) {
  MOTE_REQUIRE_DATA(intel, "intel");
  const fs::path out = scratch("nav2-params-start");
  std::ifstream gt(intel / "intel.gt.tum");
  double stamp = 0, x = 0, y = 0, z = 0, qx = 0, qy = 0, qz = 0, qw = 1;
  ASSERT_TRUE(gt >> stamp >> x >> y >> z >> qx >> qy >> qz >> qw);
  const double yaw = 2.0 * std::atan2(qz, qw);
  std::ostringstream params;
  params << std::ifstream(nav2_file()).rdbuf();
  std::string text = params.str();
  const std::string pose =
      "    set_initial_pose: true\n    initial_pose:\n      x: " + std::to_string(x) +
      "\n      y: " + std::to_string(y) + "\n      z: 0.0\n      yaw: " + std::to_string(yaw) +
      "\n";
  text.insert(text.find("    alpha1:"), pose);
  const fs::path file = out / "nav2_start.yaml";
  std::ofstream(file) << text;
  const Outcome o = mote(intel_args(intel, out / "run") + " --config '" + file.string() + "'");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  EXPECT_NE(o.out.find("mote replay: start: around " + std::to_string(x).substr(0, 4)),
            std::string::npos)
      << o.out;
  const std::string tum = last_line(slurp(out / "run" / "trajectory.tum"));
  const std::string truth = last_line(slurp(intel / "intel.gt.tum"));
  std::istringstream a(tum), b(truth);
  double ax = 0, ay = 0, bx = 0, by = 0;
  a >> stamp >> ax >> ay;
  b >> stamp >> bx >> by;
  EXPECT_LT(std::hypot(ax - bx, ay - by), 0.3) << tum << " against " << truth;
}

}  // namespace
}  // namespace mote_cli_test
