// beluga_driver: Beluga's side of bench/compare-beluga (Beluga:
// https://github.com/Ekumen-OS/beluga, a header-only C++17 MCL library; its source is the user's
// checkout, never part of this repository). Beluga's particle filter as its Amcl class composes it
// (beluga/algorithm/amcl_core.hpp: propagate, reweight, normalize, resample, estimate), with
// nav2_amcl's parameters as beluga_amcl reads them, but the particle count fixed (a resample draws
// exactly N, where Amcl would draw a KLD-adaptive count) and a resample at every update, as mote's
// side runs; no recovery (nav2's alpha_slow = alpha_fast = 0), so no random particles are mixed in.
//
//   beluga_driver --map MAP.yaml --model likelihood_field|beam --particles N --threads T
//                 --updates U [--beams B]
//
// The filter runs with std::execution::par (libstdc++'s parallel algorithms on TBB) inside a TBB
// arena of --threads threads, also for one thread: there, in three alternated pairs of runs at
// 100k particles, it took 89-97 ms per update where std::execution::seq (Amcl's default policy)
// took 93-113 ms. Prints one JSON object (beluga_scenario.hpp, print_result): the median update
// time, its phases by this driver's clock, and the final error of Beluga's estimate against the
// simulated truth.
#include <tbb/task_arena.h>

#include <Eigen/Core>
#include <beluga/actions/assign.hpp>
#include <beluga/actions/normalize.hpp>
#include <beluga/actions/propagate.hpp>
#include <beluga/actions/reweight.hpp>
#include <beluga/algorithm/estimation.hpp>
#include <beluga/containers/tuple_vector.hpp>
#include <beluga/motion/differential_drive_model.hpp>
#include <beluga/primitives.hpp>
#include <beluga/random/multivariate_normal_distribution.hpp>
#include <beluga/sensor/beam_model.hpp>
#include <beluga/sensor/data/occupancy_grid.hpp>
#include <beluga/sensor/likelihood_field_model.hpp>
#include <beluga/views/particles.hpp>
#include <beluga/views/sample.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <execution>
#include <range/v3/range/conversion.hpp>
#include <range/v3/view/take_exactly.hpp>
#include <range/v3/view/transform.hpp>
#include <sophus/se2.hpp>
#include <tuple>
#include <utility>
#include <vector>

#include "beluga_scenario.hpp"

namespace {

using Clock = std::chrono::steady_clock;
namespace peers = mote::bench::peers;

using Particle = std::tuple<Sophus::SE2d, beluga::Weight>;
using Particles = beluga::TupleVector<Particle>;

// The map as Beluga's occupancy grids read it (OccupancyGrid2 requirements: beluga/sensor/data/
// occupancy_grid.hpp): map_server's values, row-major from the bottom row.
class Grid : public beluga::BaseOccupancyGrid2<Grid> {
 public:
  struct ValueTraits {
    [[nodiscard]] static bool is_free(std::int8_t v) { return v == 0; }
    [[nodiscard]] static bool is_unknown(std::int8_t v) { return v == -1; }
    [[nodiscard]] static bool is_occupied(std::int8_t v) { return v == 100; }
  };

  explicit Grid(const peers::PlainGrid& g)
      : cells_(g.cells),
        width_(static_cast<std::size_t>(g.width)),
        height_(static_cast<std::size_t>(g.height)),
        resolution_(g.resolution),
        origin_(Sophus::SO2d(g.origin.theta), Eigen::Vector2d(g.origin.x, g.origin.y)) {}

  [[nodiscard]] const Sophus::SE2d& origin() const { return origin_; }
  [[nodiscard]] const std::vector<std::int8_t>& data() const { return cells_; }
  [[nodiscard]] std::size_t size() const { return cells_.size(); }
  [[nodiscard]] std::size_t width() const { return width_; }
  [[nodiscard]] std::size_t height() const { return height_; }
  [[nodiscard]] double resolution() const { return resolution_; }
  [[nodiscard]] ValueTraits value_traits() const { return {}; }

 private:
  std::vector<std::int8_t> cells_;
  std::size_t width_;
  std::size_t height_;
  double resolution_;
  Sophus::SE2d origin_;
};

// nav2_amcl's defaults, as beluga_amcl passes them to Beluga's models.
constexpr double kAlpha = 0.2;              // alpha1..alpha4
constexpr double kLaserMaxRange = 100.0;    // laser_max_range
constexpr double kLikelihoodMaxDist = 2.0;  // laser_likelihood_max_dist

beluga::LikelihoodFieldModelParam likelihood_field_params() {
  beluga::LikelihoodFieldModelParam p;
  p.max_obstacle_distance = kLikelihoodMaxDist;
  p.max_laser_distance = kLaserMaxRange;
  p.z_hit = 0.5;
  p.z_random = 0.5;
  p.sigma_hit = 0.2;
  return p;
}

beluga::BeamModelParam beam_params() {
  beluga::BeamModelParam p;
  p.z_hit = 0.5;
  p.z_short = 0.05;
  p.z_max = 0.05;
  p.z_rand = 0.5;
  p.sigma_hit = 0.2;
  p.lambda_short = 0.1;
  p.beam_max_range = kLaserMaxRange;
  return p;
}

Sophus::SE2d se2(const peers::PlainPose& p) {
  return Sophus::SE2d(Sophus::SO2d(p.theta), Eigen::Vector2d(p.x, p.y));
}

// The scan's valid readings as points in the base frame (the particles' frame), the measurement
// both of Beluga's range models take.
std::vector<std::pair<double, double>> points(const peers::Scenario& s, const peers::Frame& f) {
  const Sophus::SE2d sensor = se2(s.scan.sensor);
  std::vector<std::pair<double, double>> out;
  out.reserve(f.ranges.size());
  for (std::size_t i = 0; i < f.ranges.size(); ++i) {
    const double r = f.ranges[i];
    if (!std::isfinite(r) || r < s.scan.range_min || r >= s.scan.range_max) continue;
    const double a = static_cast<double>(s.scan.angle_min) +
                     static_cast<double>(i) * static_cast<double>(s.scan.angle_increment);
    const Eigen::Vector2d p = sensor * Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
    out.emplace_back(p.x(), p.y());
  }
  return out;
}

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

template <class Policy, class SensorModel>
peers::RunResult run(Policy policy, const SensorModel& sensor_model, const peers::RunArgs& args,
                     const peers::Scenario& s) {
  const beluga::DifferentialDriveModel2d motion_model({kAlpha, kAlpha, kAlpha, kAlpha});
  const auto n = static_cast<std::size_t>(args.particles);
  const peers::Frame& start = s.frames[s.frame(0)];
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) covariance(i, i) = peers::kStartVariance[i];
  Particles particles =
      beluga::views::sample(beluga::MultivariateNormalDistribution{se2(start.truth), covariance}) |
      ranges::views::transform(beluga::make_from_state<Particle>) | ranges::views::take_exactly(n) |
      ranges::to<beluga::TupleVector>;
  // The first scan only weighs, at the start pose (as mote's first update after initialize).
  particles |= beluga::actions::reweight(policy, sensor_model(points(s, start))) |
               beluga::actions::normalize(policy);

  peers::RunResult r;
  r.peer = "beluga";
  r.description =
      "Beluga's actions and views as Amcl composes them, nav2 parameters, fixed N, "
      "resample every update";
  r.updates.reserve(static_cast<std::size_t>(args.updates));
  Sophus::SE2d previous = se2(start.odometry);
  for (int k = 1; k <= args.updates; ++k) {
    const peers::Frame& frame = s.frames[s.frame(static_cast<std::size_t>(k))];
    const Sophus::SE2d odometry = se2(frame.odometry);
    const auto t0 = Clock::now();
    particles |=
        beluga::actions::propagate(policy, motion_model(std::make_tuple(odometry, previous)));
    const auto t1 = Clock::now();
    particles |= beluga::actions::reweight(policy, sensor_model(points(s, frame)));
    const auto t2 = Clock::now();
    particles |= beluga::actions::normalize(policy);
    const auto t3 = Clock::now();
    particles |= beluga::views::sample | ranges::views::take_exactly(n) | beluga::actions::assign;
    const auto t4 = Clock::now();
    const auto [mean, cov] =
        beluga::estimate(beluga::views::states(particles), beluga::views::weights(particles));
    const auto t5 = Clock::now();
    static_cast<void>(cov);
    r.updates.push_back({ms_between(t0, t1), ms_between(t1, t2), ms_between(t2, t3),
                         ms_between(t3, t4), ms_between(t4, t5), ms_between(t0, t5)});
    r.estimate = {mean.translation().x(), mean.translation().y(), mean.so2().log()};
    r.truth = frame.truth;
    r.particles = particles.size();
    r.beams = points(s, frame).size();
    previous = odometry;
  }
  return r;
}

template <class SensorModel>
peers::RunResult run_on_threads(const SensorModel& model, const peers::RunArgs& args,
                                const peers::Scenario& s) {
  tbb::task_arena arena(args.threads);
  return arena.execute([&] { return run(std::execution::par, model, args, s); });
}

peers::RunResult run(const peers::RunArgs& args, const peers::Scenario& s) {
  const Grid grid(s.grid);
  if (args.model == "beam") {
    const beluga::BeamSensorModel<Grid> model(beam_params(), grid);
    return run_on_threads(model, args, s);
  }
  const beluga::LikelihoodFieldModel<Grid> model(likelihood_field_params(), grid);
  return run_on_threads(model, args, s);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const peers::RunArgs args = peers::parse_args(argc, argv, "beluga_driver", false);
    const peers::Scenario scenario = peers::make_scenario(args.map, args.beams);
    peers::print_result(args, scenario, run(args, scenario));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beluga_driver: %s\n", e.what());
    return 1;
  }
}
