/// \file
/// The simulator's seeds, config checks, start pose and files, the bundled floor plan, and runs on
/// recorded maps of other buildings.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/sim/simulate.hpp"
#include "mote_test/data.hpp"
#include "mote_test/log_files.hpp"

namespace mote::sim {
namespace {

std::string simulate_to_bytes(const OccupancyGrid& map, std::uint64_t seed, const char* dir) {
  SimulationConfig config;
  config.seconds = 10.0;
  config.seed = seed;
  const SimulationFiles files = write_simulation(simulate(map, config), test::temp_dir() / dir);
  return test::read_bytes(files.log) + test::read_bytes(files.ground_truth);
}

TEST(SimulateSeeds, SameSeedGivesIdenticalFilesOtherSeedsDiffer) {
  const OccupancyGrid map = load_map(bundled_map_path());
  const std::string a = simulate_to_bytes(map, 7, "a");
  const std::string b = simulate_to_bytes(map, 7, "b");
  const std::string c = simulate_to_bytes(map, 8, "c");
  ASSERT_GT(a.size(), 10000U);
  EXPECT_TRUE(a == b) << "same seed, different bytes";
  EXPECT_FALSE(a == c) << "different seeds, same bytes";
}

TEST(SimulateConfig, RejectsInvalidValues) {
  const OccupancyGrid map = load_map(bundled_map_path());
  const auto rejects = [&](auto change) {
    SimulationConfig config;
    config.seconds = 1.0;
    change(config);
    EXPECT_THROW((void)simulate(map, config), ConfigError);
  };
  rejects([](SimulationConfig& c) { c.seconds = -1.0; });
  rejects([](SimulationConfig& c) { c.seconds = std::nan(""); });
  rejects([](SimulationConfig& c) { c.scan_rate = 0.0; });
  rejects([](SimulationConfig& c) { c.beams = 0; });
  rejects([](SimulationConfig& c) { c.max_range = 0.01F; });
  rejects([](SimulationConfig& c) { c.range_noise = -0.1; });
  rejects([](SimulationConfig& c) { c.dropout_probability = 0.7, c.short_probability = 0.4; });
  rejects([](SimulationConfig& c) { c.path_clearance = 0.1; });
  rejects([](SimulationConfig& c) { c.odometry.rotation = -1.0; });
  rejects([](SimulationConfig& c) { c.start = Pose2{std::nan(""), 0.0, 0.0}; });
}

TEST(SimulateConfig, MapWithoutRoomForTheRobotIsRejected) {
  const OccupancyGrid tiny(6, 6, 0.05, {}, std::vector<CellState>(36, CellState::kFree));
  EXPECT_THROW((void)simulate(tiny, SimulationConfig{}), ConfigError);
}

TEST(SimulateConfig, StartsAtTheGivenPoseAndHonoursTheLayout) {
  const OccupancyGrid map = load_map(bundled_map_path());
  SimulationConfig config;
  config.seconds = 2.0;
  config.scan_rate = 5.0;
  config.beams = 361;
  config.start = Pose2{3.0, 6.5, 0.3};  // in the corridor (map frame)
  config.start_stamp = 1700000000.25;
  const Simulation sim = simulate(map, config);
  ASSERT_EQ(sim.frames.size(), 10U);
  EXPECT_EQ(sim.truth.front().pose, *config.start);
  EXPECT_EQ(sim.frames.front().odometry, *config.start);
  EXPECT_EQ(sim.frames.front().stamp, 1700000000.25);
  EXPECT_NEAR(sim.frames.back().stamp - sim.frames.front().stamp, 1.8, 1e-6);
  EXPECT_EQ(sim.frames.front().scan.ranges.size(), 361U);
  // Epoch-sized stamps survive the TUM file too.
  const SimulationFiles files = write_simulation(sim, test::temp_dir());
  const std::vector<logs::StampedPose> truth = logs::read_tum(files.ground_truth);
  ASSERT_EQ(truth.size(), sim.truth.size());
  for (std::size_t k = 0; k < truth.size(); ++k) EXPECT_EQ(truth[k].stamp, sim.truth[k].stamp);
}

TEST(SimulateConfig, NoiselessOdometryEqualsTheTruth) {
  const OccupancyGrid map = load_map(bundled_map_path());
  SimulationConfig config;
  config.seconds = 10.0;
  config.odometry = {0.0, 0.0, 0.0, 0.0, 0.0};
  const Simulation sim = simulate(map, config);
  for (std::size_t k = 0; k < sim.frames.size(); ++k) {
    const Pose2 d = between(sim.truth[k].pose, sim.frames[k].odometry);
    ASSERT_LT(std::hypot(d.x, d.y), 1e-9) << k;
    ASSERT_LT(std::abs(d.theta), 1e-9) << k;
  }
}

TEST(SimulateFiles, RoundTripThroughTheReaders) {
  const OccupancyGrid map = load_map(bundled_map_path());
  SimulationConfig config;
  config.seconds = 20.0;
  const Simulation sim = simulate(map, config);
  const SimulationFiles files = write_simulation(sim, test::temp_dir() / "out");
  EXPECT_EQ(files.log.filename(), "sim.clf");
  EXPECT_EQ(files.ground_truth.filename(), "sim.gt.tum");
  auto source = logs::open_carmen_log(files.log);
  const std::vector<logs::ScanFrame> frames = test::read_all(*source);
  const std::vector<logs::StampedPose> truth = logs::read_tum(files.ground_truth);
  ASSERT_EQ(frames.size(), sim.frames.size());
  ASSERT_EQ(truth.size(), sim.truth.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    ASSERT_EQ(frames[k].stamp, sim.frames[k].stamp);
    ASSERT_EQ(frames[k].odometry, sim.frames[k].odometry);
    ASSERT_EQ(frames[k].scan.ranges, sim.frames[k].scan.ranges);
    ASSERT_EQ(truth[k].stamp, sim.truth[k].stamp);  // scans and poses pair up by stamp
    ASSERT_NEAR(truth[k].pose.x, sim.truth[k].pose.x, 1e-6);
    ASSERT_NEAR(truth[k].pose.y, sim.truth[k].pose.y, 1e-6);
    ASSERT_NEAR(truth[k].pose.theta, sim.truth[k].pose.theta, 1e-8);
  }
}

TEST(BundledMap, IsAnAsymmetricOfficeFloorPlan) {
  const OccupancyGrid map = load_map(bundled_map_path());
  ASSERT_EQ(map.width(), 400);
  ASSERT_EQ(map.height(), 300);
  EXPECT_DOUBLE_EQ(map.resolution(), 0.05);
  const double free =
      static_cast<double>(map.free_cell_count()) / static_cast<double>(map.cell_count());
  EXPECT_GT(free, 0.6);
  EXPECT_LT(free, 0.95);
  // Mirror images and the half turn must differ in many cells, or global localization would
  // have several equally good answers.
  std::size_t flip_x = 0;
  std::size_t flip_y = 0;
  std::size_t turn = 0;
  const int w = map.width();
  const int h = map.height();
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const CellState s = map.at({i, j});
      flip_x += s != map.at({w - 1 - i, j}) ? 1 : 0;
      flip_y += s != map.at({i, h - 1 - j}) ? 1 : 0;
      turn += s != map.at({w - 1 - i, h - 1 - j}) ? 1 : 0;
    }
  }
  const std::size_t floor = map.cell_count() / 20;
  EXPECT_GT(flip_x, floor);
  EXPECT_GT(flip_y, floor);
  EXPECT_GT(turn, floor);
}

TEST(SimulateRecordedMaps, WillowGarageRunStaysInFreeSpace) {
  MOTE_REQUIRE_DATA(yaml, "maps/willow-full-0.05.yaml");
  const OccupancyGrid map = load_map(yaml);
  SimulationConfig config;
  config.seconds = 20.0;
  const Simulation sim = simulate(map, config);
  ASSERT_EQ(sim.truth.size(), 200U);
  double travelled = 0.0;
  for (std::size_t k = 0; k < sim.truth.size(); ++k) {
    const Pose2& p = sim.truth[k].pose;
    ASSERT_EQ(map.at_or(map.world_to_cell({p.x, p.y}), CellState::kOccupied), CellState::kFree);
    if (k > 0) {
      const Pose2& q = sim.truth[k - 1].pose;
      travelled += std::hypot(p.x - q.x, p.y - q.y);
    }
  }
  EXPECT_GT(travelled, 2.0);
}

}  // namespace
}  // namespace mote::sim
