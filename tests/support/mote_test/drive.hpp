#pragma once
/// \file
/// A robot driving through a real map for the Localizer tests: its true pose, its noisy
/// odometry and the scans the simulator takes at the true pose.

#include <cstdint>
#include <numbers>

#include "mote/core/pose.hpp"
#include "mote/engine/localizer.hpp"
#include "mote_test/scan_simulator.hpp"

namespace mote::test {

struct Drive {
  Drive(const OccupancyGrid& map, Pose2 start, std::uint64_t seed)
      : sim(map, seed), truth(start), odometry{1.0, -2.0, 0.3} {}

  // Moves the robot and returns the odometry pose; the odometry increment is the true one
  // with 1 cm and 0.5 degree of noise.
  Pose2 advance() {
    constexpr double kDeg = std::numbers::pi / 180.0;
    const Pose2 next = sim.drive(truth);
    Pose2 step = between(truth, next);
    step.x += 0.01 * sim.normal();
    step.y += 0.01 * sim.normal();
    step.theta += 0.5 * kDeg * sim.normal();
    truth = next;
    odometry = compose(odometry, step);
    return odometry;
  }

  // Moves the robot one step and feeds the filter its odometry and the scan taken there.
  bool feed(Localizer& filter) {
    const Pose2 odom = advance();
    return filter.update(odom, sim.scan_at(truth));
  }

  ScanSimulator sim;
  Pose2 truth;
  Pose2 odometry;
};

}  // namespace mote::test
