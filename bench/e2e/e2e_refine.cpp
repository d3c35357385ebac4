// ScanMatcher::match as the Localizer runs it after each update (localizer_steps.cpp,
// judge_localization): every valid reading of the scan, the Cauchy scale sigma_hit of mote's
// defaults, from a start near the pose (here the true pose moved by 5 cm and 1 degree, where the
// best hypothesis's mean lies when tracking). Read beside BM_Localizer_Update/likelihood_field/
// tracking/n:1000/beams:<b>/threads:1, whose update includes one such match: the ratio is the
// refinement's share of a tracking update at the particle counts mote's defaults settle at.
#include "e2e_refine.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "e2e_world.hpp"
#include "mote/engine/beams.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/engine/scan_match.hpp"
#include "mote/maps/signed_distance_field.hpp"

namespace mote::bench {

namespace {

// The scan's endpoints in the robot frame as Localizer::Impl::select_endpoints makes them: every
// reading select_beams keeps (no decimation, no no-returns), placed from the sensor's pose.
std::vector<Point2> endpoints(const LaserScan& scan) {
  BeamSet readings;
  select_beams(scan,
               BeamSelection{.max_beams = std::numeric_limits<int>::max(), .keep_max_range = false},
               readings);
  std::vector<Point2> ends;
  const Pose2& s = readings.sensor_pose;
  for (std::size_t b = 0; b < readings.size(); ++b) {
    const double a = s.theta + readings.angle[b];
    ends.push_back({s.x + readings.range[b] * std::cos(a), s.y + readings.range[b] * std::sin(a)});
  }
  return ends;
}

const SignedDistanceField& field() {
  static const SignedDistanceField f(
      world().map, static_cast<float>(LocalizerConfig{}.laser_likelihood_max_dist));
  return f;
}

void BM_ScanMatch_Refine(benchmark::State& state, int beams) {
  const World& w = world();
  std::vector<std::vector<Point2>> ends;  // per frame, built outside the timed loop
  for (std::size_t f = 0; f < w.truth.size(); ++f) ends.push_back(endpoints(w.scan(beams, f)));
  const ScanMatcher matcher(field(), ScanMatchConfig{.scale = LocalizerConfig{}.sigma_hit});
  std::uint64_t k = 0;
  double iterations = 0.0;
  double readings = 0.0;
  for (auto _ : state) {
    const std::size_t f = w.frame(++k);
    const Pose2& t = w.truth[f];
    const ScanMatch m = matcher.match(ends[f], {t.x + 0.04, t.y - 0.03, t.theta + 0.0175});
    benchmark::DoNotOptimize(m);
    iterations += m.iterations;
    readings += static_cast<double>(m.endpoints);
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["matches/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["iterations"] = iterations / n;
  state.counters["endpoints"] = readings / n;
}

}  // namespace

void register_refine_cases() {
  for (const int beams : kBeamCounts) {
    const std::string name = "BM_ScanMatch_Refine/beams:" + std::to_string(beams);
    benchmark::RegisterBenchmark(name.c_str(), BM_ScanMatch_Refine, beams)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace mote::bench
