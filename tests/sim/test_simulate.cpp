/// \file
/// The simulator on the bundled floor plan: collision-free true path, scans that match a ray
/// cast from the true pose within the configured noise, odometry whose errors have the
/// configured statistics; collision freedom also over many seeds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote/sim/simulate.hpp"
#include "mote_test/log_files.hpp"

namespace mote::sim {
namespace {

/// One default 60 s run on the bundled map, shared by the tests that only read it.
struct SimulatedRun {
  OccupancyGrid map;
  Simulation sim;

  static const SimulatedRun& default_run() {
    static const SimulatedRun run = [] {
      OccupancyGrid grid = load_map(bundled_map_path());
      Simulation drive = simulate(grid, SimulationConfig{});
      return SimulatedRun{std::move(grid), std::move(drive)};
    }();
    return run;
  }
};

bool blocking(const OccupancyGrid& map, CellIndex c) {
  return map.at_or(c, CellState::kOccupied) != CellState::kFree;
}

/// Distance (m) from p to the nearest point of a blocking cell, searching `reach` metres.
double clearance(const OccupancyGrid& map, Point2 p, double reach) {
  const CellIndex c = map.world_to_cell(p);
  const Point2 g = map.to_grid_frame(p);
  const double res = map.resolution();
  const int cells = static_cast<int>(std::ceil(reach / res));
  double best = reach;
  for (int j = c.j - cells; j <= c.j + cells; ++j) {
    for (int i = c.i - cells; i <= c.i + cells; ++i) {
      if (!blocking(map, {i, j})) continue;
      const double dx = std::max({i * res - g.x, 0.0, g.x - (i + 1) * res});
      const double dy = std::max({j * res - g.y, 0.0, g.y - (j + 1) * res});
      best = std::min(best, std::hypot(dx, dy));
    }
  }
  return best;
}

/// True when every point of the straight segment a-b (1 cm steps) lies in a free cell.
bool segment_free(const OccupancyGrid& map, const Pose2& a, const Pose2& b) {
  const int steps = static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / 0.01)) + 1;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    if (blocking(map, map.world_to_cell({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}))) {
      return false;
    }
  }
  return true;
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (const double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

double stddev(const std::vector<double>& v) {
  const double m = mean(v);
  double sum = 0.0;
  for (const double x : v) sum += (x - m) * (x - m);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

/// Simulated ranges minus a fresh ray cast from the true sensor pose.
struct RangeResiduals {
  std::size_t total = 0;     ///< beams compared
  std::size_t outliers = 0;  ///< beams more than 4 sigma off (dropouts included)
  std::size_t dropouts = 0;  ///< max-range readings where the cast hit a wall
  double mean = 0.0;         ///< m, of the inlier residuals on beams that hit a wall
  double std = 0.0;          ///< m, same
};

RangeResiduals range_residuals(const OccupancyGrid& map, const Simulation& sim, double sigma) {
  const RayCaster caster(map);
  RangeResiduals out;
  std::vector<double> inliers;
  for (std::size_t k = 0; k < sim.frames.size(); ++k) {
    const LaserScan& scan = sim.frames[k].scan;
    const Pose2 sensor = compose(sim.truth[k].pose, scan.sensor_pose);
    for (std::size_t b = 0; b < scan.ranges.size(); ++b) {
      const float expected =
          caster.cast_one({sensor.x, sensor.y}, sensor.theta + scan.beam_angle(b), scan.range_max);
      const double residual = static_cast<double>(scan.ranges[b]) - expected;
      ++out.total;
      if (std::abs(residual) > 4.0 * sigma) {
        ++out.outliers;
        if (scan.ranges[b] == scan.range_max) ++out.dropouts;
      } else if (expected < scan.range_max) {
        inliers.push_back(residual);
      }
    }
  }
  out.mean = mean(inliers);
  out.std = stddev(inliers);
  return out;
}

/// Odometry increment errors as z-scores against the configured model (OdometryNoise).
struct OdometryErrors {
  std::vector<double> translation;
  std::vector<double> rotation;
};

OdometryErrors odometry_errors(const Simulation& sim, const OdometryNoise& noise) {
  OdometryErrors out;
  for (std::size_t k = 1; k < sim.frames.size(); ++k) {
    const Pose2 t = between(sim.truth[k - 1].pose, sim.truth[k].pose);
    const Pose2 o = between(sim.frames[k - 1].odometry, sim.frames[k].odometry);
    const double trans = std::hypot(t.x, t.y);
    if (trans > 1e-3) {
      const double biased = trans * (1.0 + noise.translation_bias);
      out.translation.push_back((std::hypot(o.x, o.y) - biased) / (noise.translation * trans));
    }
    const double rot_std = std::hypot(noise.rotation * t.theta, noise.rotation_per_metre * trans);
    if (rot_std > 1e-6) {
      const double biased = t.theta * (1.0 + noise.rotation_bias);
      out.rotation.push_back(wrap_angle(o.theta - biased) / rot_std);
    }
  }
  return out;
}

/// Every true pose in a free cell with the robot's radius of free space around it (less the
/// cell half-diagonal that the planner's cell-centre clearance leaves open), and every straight
/// step between consecutive poses through free cells only.
void expect_collision_free(const OccupancyGrid& map, const std::vector<logs::StampedPose>& truth,
                           double robot_radius) {
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const Pose2& p = truth[k].pose;
    ASSERT_FALSE(blocking(map, map.world_to_cell({p.x, p.y}))) << "scan " << k;
    ASSERT_GE(clearance(map, {p.x, p.y}, 0.5), robot_radius - 0.75 * map.resolution()) << k;
    if (k > 0) {
      ASSERT_TRUE(segment_free(map, truth[k - 1].pose, p)) << "step " << k;
    }
  }
}

double path_length(const std::vector<logs::StampedPose>& truth) {
  double length = 0.0;
  for (std::size_t k = 1; k < truth.size(); ++k) {
    length +=
        std::hypot(truth[k].pose.x - truth[k - 1].pose.x, truth[k].pose.y - truth[k - 1].pose.y);
  }
  return length;
}

TEST(Simulate, TruePathNeverTouchesBlockingCells) {
  const SimulatedRun& run = SimulatedRun::default_run();
  ASSERT_EQ(run.sim.truth.size(), 600U);  // 60 s at 10 Hz
  expect_collision_free(run.map, run.sim.truth, SimulationConfig{}.robot_radius);
}

TEST(Simulate, EverySeedDrivesCollisionFreeWithoutGettingStuck) {
  const OccupancyGrid map = load_map(bundled_map_path());
  for (std::uint64_t seed = 100; seed < 116; ++seed) {
    SimulationConfig config;
    config.seconds = 30.0;
    config.seed = seed;
    const Simulation sim = simulate(map, config);
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_collision_free(map, sim.truth, config.robot_radius);
    EXPECT_GT(path_length(sim.truth), 0.5 * config.speed * config.seconds);
  }
}

TEST(Simulate, RobotTravelsBetweenGoalsAtTheConfiguredSpeed) {
  const SimulatedRun& run = SimulatedRun::default_run();
  double travelled = 0.0;
  double fastest = 0.0;
  for (std::size_t k = 1; k < run.sim.truth.size(); ++k) {
    const Pose2 d = between(run.sim.truth[k - 1].pose, run.sim.truth[k].pose);
    travelled += std::hypot(d.x, d.y);
    fastest = std::max(fastest, std::hypot(d.x, d.y) / 0.1);
  }
  EXPECT_GT(travelled, 0.5 * 0.5 * 60.0);  // at least half the time at cruise speed
  EXPECT_LE(fastest, 0.5 + 1e-9);
  EXPECT_GE(run.sim.goals_reached, 2U);
}

TEST(Simulate, ScanGeometryFollowsTheConfig) {
  const SimulatedRun& run = SimulatedRun::default_run();
  const LaserScan& scan = run.sim.frames.front().scan;
  ASSERT_EQ(scan.ranges.size(), 181U);
  EXPECT_FLOAT_EQ(scan.angle_min, static_cast<float>(-std::numbers::pi / 2));
  EXPECT_FLOAT_EQ(scan.angle_increment, static_cast<float>(std::numbers::pi / 180));
  EXPECT_EQ(scan.range_max, 20.0F);
  EXPECT_EQ(scan.range_min, 0.05F);
  EXPECT_EQ(scan.sensor_pose, (Pose2{0.1, 0.0, 0.0}));
  for (std::size_t k = 0; k < run.sim.frames.size(); ++k) {
    EXPECT_EQ(run.sim.frames[k].stamp, run.sim.truth[k].stamp);
    EXPECT_EQ(run.sim.frames[k].scan.stamp, run.sim.truth[k].stamp);
  }
}

TEST(Simulate, RangesMatchARayCastFromTheTruePoseWithinTheNoise) {
  const SimulatedRun& run = SimulatedRun::default_run();
  const SimulationConfig config;
  const RangeResiduals r = range_residuals(run.map, run.sim, config.range_noise);
  const double n = static_cast<double>(r.total);
  // Beams outside 4 sigma are the dropouts and short readings, nothing else.
  EXPECT_NEAR(static_cast<double>(r.outliers) / n,
              config.dropout_probability + config.short_probability, 0.006);
  EXPECT_NEAR(r.mean, 0.0, 0.05 * config.range_noise);
  EXPECT_GT(r.std, 0.8 * config.range_noise);
  EXPECT_LT(r.std, 1.2 * config.range_noise);
  EXPECT_GT(static_cast<double>(r.dropouts) / n, 0.5 * config.dropout_probability);
}

TEST(Simulate, OdometryErrorsHaveTheConfiguredStatistics) {
  const SimulatedRun& run = SimulatedRun::default_run();
  const OdometryErrors e = odometry_errors(run.sim, SimulationConfig{}.odometry);
  ASSERT_GT(e.translation.size(), 400U);
  ASSERT_GT(e.rotation.size(), 400U);
  // z-scores: (reported - biased true) / configured std; mean near 0, std within a factor 2.
  EXPECT_NEAR(mean(e.translation), 0.0, 0.2);
  EXPECT_NEAR(mean(e.rotation), 0.0, 0.2);
  EXPECT_GT(stddev(e.translation), 0.5);
  EXPECT_LT(stddev(e.translation), 2.0);
  EXPECT_GT(stddev(e.rotation), 0.5);
  EXPECT_LT(stddev(e.rotation), 2.0);
  // Integrated, the errors drift: the final odometry pose is off the true one.
  const Pose2 drift = between(run.sim.truth.back().pose, run.sim.frames.back().odometry);
  EXPECT_GT(std::hypot(drift.x, drift.y) + std::abs(drift.theta), 1e-3);
}

}  // namespace
}  // namespace mote::sim
