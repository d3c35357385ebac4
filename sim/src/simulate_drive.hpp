#pragma once
/// \file
/// The simulated robot's motion: a differential drive (unicycle) that picks random reachable
/// goals, plans a path to each and follows it with a pure pursuit controller (Coulter,
/// "Implementation of the pure pursuit path tracking algorithm", CMU-RI-TR-92-01), never entering a
/// cell closer than the robot radius to a blocking cell.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/engine/philox.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/sim/simulate.hpp"
#include "simulate_planner.hpp"

namespace mote::sim::detail {

/// Drives the true robot pose through a map. The map must outlive the driver.
class Driver {
 public:
  /// Builds the clearance masks and places the robot (config.start, or a random clear cell of
  /// the largest connected free region). Throws ConfigError when no cell is clear.
  Driver(const OccupancyGrid& map, const SimulationConfig& config);

  /// Moves the robot for dt seconds (one control step); picks a new goal on arrival.
  void advance(double dt);

  [[nodiscard]] const Pose2& pose() const noexcept { return pose_; }
  [[nodiscard]] std::size_t goals_reached() const noexcept { return goals_reached_; }

 private:
  void place_robot();
  void new_goal();
  /// A uniformly drawn cell of region_ (which must not be empty).
  [[nodiscard]] CellIndex draw_cell(const RngStream& rng) const;
  [[nodiscard]] Point2 lookahead_point();
  [[nodiscard]] bool may_enter(const Pose2& next) const;

  const SimulationConfig* config_;
  ClearanceMask safe_;  ///< robot_radius: where the true pose may go
  ClearanceMask plan_;  ///< path_clearance: where paths are planned
  PathPlanner planner_;
  std::vector<std::uint32_t> region_;  ///< cells goals are drawn from
  std::vector<Point2> path_;           ///< waypoints to the current goal, map frame (m)
  std::size_t segment_ = 0;            ///< index of the path segment being followed
  std::uint64_t goal_draws_ = 0;       ///< counter of the goal random stream
  double stuck_time_ = 0.0;            ///< s spent unable to move forward
  std::size_t goals_reached_ = 0;
  Pose2 pose_;
};

}  // namespace mote::sim::detail
