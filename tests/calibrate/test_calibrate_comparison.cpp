// The fitted config against the starting one: which is better, the verdict's words and
// comparison.yaml, for the ATE (lower is better) and the scan fit (higher is better).
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "mote/calibrate/calibrate.hpp"

namespace mote::calibrate {
namespace {

StartComparison ate(double fitted, double start) {
  return {.metric = "ate_rmse_m",
          .fitted = fitted,
          .start = start,
          .start_name = "mote's defaults",
          .min_particles = 5000,
          .max_particles = 5000,
          .seed = 42};
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CalibrationComparison, AWorseFitSaysKeepTheDefaults) {
  const StartComparison c = ate(0.0371, 0.0314);
  EXPECT_FALSE(fitted_is_better(c));
  const std::string v = comparison_verdict(c, "out/config.yaml");
  EXPECT_TRUE(has(v, "NOT better than mote's defaults: ATE 0.0371 m against 0.0314 m")) << v;
  EXPECT_TRUE(has(v, "0.0314 m (5000 particles, seed 42); keep")) << v;
  EXPECT_TRUE(has(v, "keep mote's defaults (run without --config)")) << v;
  EXPECT_FALSE(has(v, "out/config.yaml")) << v;
  EXPECT_TRUE(has(comparison_yaml(c), "\nbetter: start\n")) << comparison_yaml(c);
}

TEST(CalibrationComparison, ABetterFitNamesItsConfig) {
  const StartComparison c = ate(0.0290, 0.0314);
  EXPECT_TRUE(fitted_is_better(c));
  const std::string v = comparison_verdict(c, "out/config.yaml");
  EXPECT_TRUE(has(v, "is better than mote's defaults: ATE 0.0290 m against 0.0314 m")) << v;
  EXPECT_TRUE(has(v, "run with --config out/config.yaml")) << v;
  EXPECT_TRUE(has(comparison_yaml(c), "\nbetter: fitted\n")) << comparison_yaml(c);
}

TEST(CalibrationComparison, ATieKeepsTheStartingFile) {
  StartComparison c = ate(0.0314, 0.0314);
  c.start_name = "my.yaml";
  c.max_particles = 20000;
  EXPECT_FALSE(fitted_is_better(c));
  const std::string v = comparison_verdict(c, "out/config.yaml");
  EXPECT_TRUE(has(v, "keep my.yaml (run with --config my.yaml)")) << v;
  EXPECT_TRUE(has(v, "5000-20000 particles")) << v;
}

TEST(CalibrationComparison, ScanFitIsHigherIsBetter) {
  StartComparison c = ate(1.66, 1.64);
  c.metric = "scan_fit";
  EXPECT_TRUE(fitted_is_better(c));
  EXPECT_TRUE(
      has(comparison_verdict(c, "c.yaml"), "scan fit at the estimates 1.6600 against 1.6400 nats"));
  c.fitted = 1.63;
  EXPECT_FALSE(fitted_is_better(c));
}

TEST(CalibrationComparison, ARunWithoutAFigureLoses) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(fitted_is_better(ate(kNaN, 0.03)));
  EXPECT_TRUE(fitted_is_better(ate(0.03, kNaN)));
}

}  // namespace
}  // namespace mote::calibrate
