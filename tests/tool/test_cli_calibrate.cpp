// `mote calibrate` and the simulator's noise knobs, run as the user runs them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_test_util.hpp"

namespace mote_cli_test {
namespace {

const fs::path kMap = fs::path(MOTE_SOURCE_DIR) / "sim/data/floorplan.yaml";

// The number of lines of `text` that start with `prefix`.
int lines_starting(const std::string& text, const std::string& prefix) {
  int n = 0;
  for (std::size_t at = 0; at < text.size(); at = text.find('\n', at) + 1) {
    n += text.compare(at, prefix.size(), prefix) == 0;
    if (text.find('\n', at) == std::string::npos) break;
  }
  return n;
}

// The number after "KEY: " on a line of a flat YAML text (NaN when absent).
double yaml_number(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(std::string("\n").append(key).append(": "));
  return at == std::string::npos ? std::nan("") : std::stod(text.substr(at + key.size() + 3));
}

// The number after the first "KEY": in a JSON text (NaN when absent).
double json_number(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(std::string("\"").append(key).append("\":"));
  return at == std::string::npos ? std::nan("") : std::stod(text.substr(at + key.size() + 3));
}

TEST(CliCalibrate, SimulatedLogGivesALoadableConfigAndPicture) {
  const fs::path dir = scratch("calibrate_ok");
  const Outcome sim = mote("simulate --map '" + kMap.string() + "' --out '" + dir.string() +
                           "' --seconds 200 --scan-rate 1.5 --alphas 0.1,0.02,0.05,0.02 "
                           "--mixture 0.8,0.1,0.05,0.05 --mixture-shape 0.05,0.5");
  ASSERT_EQ(sim.status, 0) << sim.err;
  const std::string noise = slurp(dir / "sim.noise.yaml");
  EXPECT_NE(noise.find("alpha3: 0.05"), std::string::npos) << noise;
  EXPECT_NE(noise.find("sigma_hit: 0.05"), std::string::npos) << noise;
  const fs::path out = dir / "calib";
  const Outcome cal =
      mote("calibrate --map '" + kMap.string() + "' --log '" + (dir / "sim.clf").string() +
           "' --reference '" + (dir / "sim.gt.tum").string() + "' --out '" + out.string() + "'");
  ASSERT_EQ(cal.status, 0) << cal.err;
  EXPECT_NE(cal.out.find("beam          z_hit"), std::string::npos) << cal.out;
  // One verdict line per fitted group.
  EXPECT_NE(cal.out.find("\nsensor: fitted once against the reference poses"), std::string::npos)
      << cal.out;
  EXPECT_NE(cal.out.find("\nodometry: fitted once against the reference poses"), std::string::npos)
      << cal.out;
  EXPECT_GT(fs::file_size(out / "calibration.png"), 1000U);
  // The config drives a replay, and the verdict's ATE with it is that replay's.
  const Outcome rep =
      mote("replay --map '" + kMap.string() + "' --log '" + (dir / "sim.clf").string() +
           "' --reference '" + (dir / "sim.gt.tum").string() + "' --config '" +
           (out / "config.yaml").string() + "' --out '" + (dir / "rep").string() + "' --quiet");
  EXPECT_EQ(rep.status, 0) << rep.err;
  EXPECT_EQ(lines_starting(cal.out,
                           "verdict: replayed with both on this log, the fitted config "
                           "is "),
            1)
      << cal.out;
  const std::string comparison = slurp(out / "comparison.yaml");
  EXPECT_NE(comparison.find("metric: ate_rmse_m"), std::string::npos) << comparison;
  const double fitted = yaml_number(comparison, "fitted");
  EXPECT_NEAR(fitted, json_number(slurp(dir / "rep" / "report.json"), "ate_rmse_m"), 1e-5)
      << comparison;
  const bool better = comparison.find("\nbetter: fitted\n") != std::string::npos;
  EXPECT_EQ(better, fitted < yaml_number(comparison, "start")) << comparison;
  EXPECT_EQ(better,
            cal.out.find("config is better than mote's defaults: ATE ") != std::string::npos)
      << cal.out;
  EXPECT_EQ(!better,
            cal.out.find("keep mote's defaults (run without --config)") != std::string::npos)
      << cal.out;
}

// Without a reference: one verdict per group, one round is never converged, and the
// parameters named on a bound are the config's.
TEST(CliCalibrate, SelfCalibrationEndsWithAVerdictPerGroup) {
  const fs::path dir = scratch("calibrate_verdict");
  ASSERT_EQ(mote("simulate --map '" + kMap.string() + "' --out '" + dir.string() +
                 "' --seconds 200 --scan-rate 1.5")
                .status,
            0);
  const std::string run =
      "calibrate --map '" + kMap.string() + "' --log '" + (dir / "sim.clf").string() + "' --out '";
  const Outcome one = mote(run + (dir / "one").string() + "' --rounds 1");
  ASSERT_EQ(one.status, 0) << one.err;
  for (const char* group : {"sensor", "odometry"}) {
    EXPECT_EQ(lines_starting(one.out, std::string(group) + ": NOT converged: one round"), 1)
        << one.out;
  }
  const Outcome three = mote(run + (dir / "three").string() + "'");  // the default rounds
  ASSERT_EQ(three.status, 0) << three.err;
  for (const char* group : {"sensor: ", "odometry: "}) {
    const std::string g(group);
    // The round it settles in may differ in the filter's last bits between compilers.
    int verdicts = lines_starting(three.out, g + "settled within its statistical spread") +
                   lines_starting(three.out, g + "NOT converged: round limit");
    for (int n = 2; n <= 6; ++n)
      verdicts += lines_starting(three.out, g + "converged in " + std::to_string(n) + " rounds");
    EXPECT_EQ(verdicts, 1) << three.out;
  }
  // Then the fitted config against the defaults, by the scans' fit without a reference: the
  // words say which one to run, as comparison.yaml does.
  const std::string comparison = slurp(dir / "three" / "comparison.yaml");
  EXPECT_NE(comparison.find("metric: scan_fit"), std::string::npos) << comparison;
  const bool better = comparison.find("\nbetter: fitted\n") != std::string::npos;
  EXPECT_EQ(better, yaml_number(comparison, "fitted") > yaml_number(comparison, "start"))
      << comparison;
  const std::string verdict = "verdict: replayed with both on this log, the fitted config is ";
  EXPECT_EQ(lines_starting(three.out, verdict + (better ? "better than mote's defaults: scan fit"
                                                        : "NOT better than mote's defaults: "
                                                          "scan fit")),
            1)
      << three.out;
  const std::string config = slurp(dir / "three" / "config.yaml");
  int at_bound = 0;
  for (std::size_t at = config.find("# AT BOUND"); at != std::string::npos;
       at = config.find("# AT BOUND", at + 1)) {
    ++at_bound;
  }
  EXPECT_EQ(lines_starting(three.out, "sensor: parameter at its bound: ") +
                lines_starting(three.out, "odometry: parameter at its bound: "),
            at_bound)
      << three.out << config;
}

TEST(CliCalibrate, ShortLogIsOneLineAndNoConfig) {
  const fs::path dir = scratch("calibrate_short");
  ASSERT_EQ(mote("simulate --map '" + kMap.string() + "' --out '" + dir.string() + "' --seconds 5")
                .status,
            0);
  const fs::path out = dir / "calib";
  const Outcome cal = mote("calibrate --map '" + kMap.string() + "' --log '" +
                           (dir / "sim.clf").string() + "' --out '" + out.string() + "'");
  EXPECT_EQ(cal.status, 1);
  EXPECT_EQ(lines(cal.err), 1) << cal.err;
  EXPECT_NE(cal.err.find("log too short"), std::string::npos) << cal.err;
  EXPECT_FALSE(fs::exists(out / "config.yaml"));
}

TEST(CliCalibrate, NoiseKnobsCheckTheirValues) {
  const fs::path dir = scratch("calibrate_knobs");
  const Outcome bad =
      mote("simulate --map '" + kMap.string() + "' --out '" + dir.string() + "' --alphas 0.1,0.2");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--alphas"), std::string::npos) << bad.err;
  const Outcome sum = mote("simulate --map '" + kMap.string() + "' --out '" + dir.string() +
                           "' --mixture 0.5,0.1,0.1,0.1");
  EXPECT_EQ(sum.status, 1);
  EXPECT_NE(sum.err.find("sum to 1"), std::string::npos) << sum.err;
}

}  // namespace
}  // namespace mote_cli_test
