// The refined estimate's gate on every shared log, measured: while the filter tracks, the belief
// and the match describe the same pose, and the gate at 0.999 should refuse about one update in
// a thousand. The Laplace covariance of a match that took hundreds of correlated readings as
// independent refused 1-2.6 %. The bound is twice the nominal share, tested as a binomial
// count: a log fails when its refusals are less likely than 1 % at that rate (one refusal in a
// few hundred updates is not evidence of a miscalibrated gate; 9 of 902 is). Each test replays
// a whole log with mote's defaults (from the first reference pose, or globally where a log has
// none): label `long`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>

#include "mote/replay/replay_run.hpp"
#include "mote_test/data.hpp"

namespace mote {
namespace {

constexpr double kNominal = 0.001;  // 1 - the gate's quantile
constexpr double kSignificance = 0.01;

// P(X >= k) for X ~ Binomial(n, p), summed in log space.
double upper_tail(std::size_t k, std::size_t n, double p) {
  double below = 0.0;  // P(X < k)
  for (std::size_t i = 0; i < k && i <= n; ++i) {
    const double log_term =
        std::lgamma(static_cast<double>(n) + 1.0) - std::lgamma(static_cast<double>(i) + 1.0) -
        std::lgamma(static_cast<double>(n - i) + 1.0) + static_cast<double>(i) * std::log(p) +
        static_cast<double>(n - i) * std::log1p(-p);
    below += std::exp(log_term);
  }
  return std::max(0.0, 1.0 - below);
}

struct GateCount {
  std::size_t tracking = 0;  // updates that ended tracking with a converged match
  std::size_t gated = 0;     // of those, matches the gate refused
};

// `reference` empty: a global start.
GateCount count_gate(const std::string& yaml_rel, const std::string& log_rel,
                     const std::string& reference_rel);

void expect_gate_calibrated(const std::string& yaml_rel, const std::string& log_rel,
                            const std::string& reference_rel) {
  for (const std::string& rel : {yaml_rel, log_rel}) {
    const std::filesystem::path p = test::data_dir() / rel;
    if (!std::filesystem::exists(p)) GTEST_SKIP() << "recorded data not found: " << p;
  }
  const GateCount count = count_gate(yaml_rel, log_rel, reference_rel);
  ASSERT_GT(count.tracking, 20U);
  ::testing::Test::RecordProperty("gated", static_cast<int>(count.gated));
  ::testing::Test::RecordProperty("tracking", static_cast<int>(count.tracking));
  std::printf("gate refused %zu of %zu tracking updates\n", count.gated, count.tracking);
  EXPECT_GE(upper_tail(count.gated, count.tracking, 2.0 * kNominal), kSignificance)
      << count.gated << " of " << count.tracking << " tracking updates refused by the gate";
}

GateCount count_gate(const std::string& yaml_rel, const std::string& log_rel,
                     const std::string& reference_rel) {
  replay::ReplayOptions o;
  o.map = test::data_dir() / yaml_rel;
  o.log = test::data_dir() / log_rel;
  if (!reference_rel.empty()) o.reference = test::data_dir() / reference_rel;
  o.init = reference_rel.empty() ? replay::InitMode::kGlobal : replay::InitMode::kAuto;
  o.config.seed = 1;
  GateCount count;
  o.on_update = [&count](const Localizer& filter, const logs::ScanFrame&) {
    const UpdateStats& u = filter.last_update();
    if (u.state != LocalizationState::kTracking) return;
    if (!u.refined_matched && !u.refined_gated) return;  // no converged match to judge
    ++count.tracking;
    count.gated += u.refined_gated ? 1 : 0;
  };
  (void)replay::run_replay(o);
  return count;
}

TEST(RefinedGateOnLogs, TheBinomialBoundCanFail) {
  EXPECT_LT(upper_tail(9, 902, 2.0 * kNominal), kSignificance);  // the chi-square gate on Intel
  EXPECT_GE(upper_tail(1, 383, 2.0 * kNominal), kSignificance);
  EXPECT_DOUBLE_EQ(upper_tail(0, 100, 0.5), 1.0);
}

TEST(RefinedGateOnLogs, Intel) {
  expect_gate_calibrated("intel/intel.yaml", "intel/intel.clf", "intel/intel.gt.tum");
}
TEST(RefinedGateOnLogs, Acapulco) {
  expect_gate_calibrated("dev/acapulco/acapulco.yaml", "dev/acapulco/acapulco.clf",
                         "dev/acapulco/acapulco.gt.tum");
}
TEST(RefinedGateOnLogs, Belgioioso) {
  expect_gate_calibrated("dev/belgioioso/belgioioso.yaml", "dev/belgioioso/belgioioso.clf",
                         "dev/belgioioso/belgioioso.gt.tum");
}
TEST(RefinedGateOnLogs, Edmonton) {
  expect_gate_calibrated("dev/edmonton/edmonton.yaml", "dev/edmonton/edmonton.clf",
                         "dev/edmonton/edmonton.gt.tum");
}
TEST(RefinedGateOnLogs, Freiburg101) {
  expect_gate_calibrated("dev/freiburg-101/freiburg-101.yaml", "dev/freiburg-101/freiburg-101.clf",
                         "dev/freiburg-101/freiburg-101.gt.tum");
}
TEST(RefinedGateOnLogs, Wean) {
  expect_gate_calibrated("wean/wean_map.yaml", "wean/robotdata1.clf", "");
}
TEST(RefinedGateOnLogs, Dis) {
  expect_gate_calibrated("dis/dis_underground.yaml", "dis/dis-underground.bag", "");
}
TEST(RefinedGateOnLogs, Ros2) {
  expect_gate_calibrated("ros2/mac_1st_floor_9_23.yaml", "ros2/mac_take2_zstd.mcap", "");
}

}  // namespace
}  // namespace mote
