/// \file
/// Goal selection, path following and unicycle integration of the simulated robot.

#include "simulate_drive.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mote/core/error.hpp"
#include "simulate_sensor.hpp"

namespace mote::sim::detail {
namespace {

constexpr double kLookahead = 0.3;      // m, pure pursuit look-ahead distance
constexpr double kArrived = 0.15;       // m, a goal closer than this is reached
constexpr double kMinGoalDistance = 2;  // m, goals are at least this far (straight line)
constexpr double kTurnGain = 2.0;       // 1/s, turn rate per rad of heading error
constexpr double kTurnInPlace = 0.6;    // rad, larger heading errors stop forward motion
constexpr double kGiveUp = 2.0;         // s blocked before a new goal is chosen
constexpr int kGoalTries = 32;

double distance(Point2 a, Point2 b) { return std::hypot(b.x - a.x, b.y - a.y); }

/// Exact unicycle motion for dt seconds at speed v (m/s) and turn rate w (rad/s)
/// (Thrun et al., eq. 5.9).
Pose2 integrate(const Pose2& p, double v, double w, double dt) {
  if (std::abs(w) < 1e-9) {
    return {p.x + v * dt * std::cos(p.theta), p.y + v * dt * std::sin(p.theta), p.theta};
  }
  const double r = v / w;
  const double theta = p.theta + w * dt;
  return {p.x + r * (std::sin(theta) - std::sin(p.theta)),
          p.y - r * (std::cos(theta) - std::cos(p.theta)), wrap_angle(theta)};
}

}  // namespace

Driver::Driver(const OccupancyGrid& map, const SimulationConfig& config)
    : config_(&config),
      safe_(map, config.robot_radius),
      plan_(map, config.path_clearance),
      planner_(plan_) {
  place_robot();
  new_goal();
}

void Driver::place_robot() {
  const OccupancyGrid& map = plan_.grid();
  if (config_->start) {
    pose_ = *config_->start;
    region_ = planner_.reachable(map.world_to_cell({pose_.x, pose_.y}));
    return;
  }
  region_ = planner_.largest_region();
  if (region_.empty()) {
    throw ConfigError("simulate: no map cell has path_clearance of free space around it");
  }
  const RngStream rng{.seed = config_->seed, .step = 0, .purpose = kSimGoals};
  const Point2 c = map.cell_center(draw_cell(rng));
  pose_ = {c.x, c.y, wrap_angle(2.0 * std::numbers::pi * rng.uniform_double(0, 1))};
}

CellIndex Driver::draw_cell(const RngStream& rng) const {
  const auto count = static_cast<double>(region_.size());
  const auto pick =
      std::min(static_cast<std::size_t>(rng.uniform_double(0) * count), region_.size() - 1);
  const auto w = static_cast<std::uint32_t>(plan_.grid().width());
  return {static_cast<int>(region_[pick] % w), static_cast<int>(region_[pick] / w)};
}

void Driver::new_goal() {
  const OccupancyGrid& map = plan_.grid();
  const Point2 here{pose_.x, pose_.y};
  path_.clear();
  segment_ = 0;
  for (int attempt = 0; attempt < kGoalTries && !region_.empty(); ++attempt) {
    const RngStream rng{.seed = config_->seed, .step = ++goal_draws_, .purpose = kSimGoals};
    const CellIndex goal = draw_cell(rng);
    if (distance(here, map.cell_center(goal)) < kMinGoalDistance) continue;
    path_ = planner_.plan(here, goal);
    if (path_.size() >= 2) return;
  }
}

Point2 Driver::lookahead_point() {
  const Point2 here{pose_.x, pose_.y};
  // Move on to the next segment once its start is within the look-ahead distance.
  while (segment_ + 2 < path_.size() && distance(here, path_[segment_ + 1]) < kLookahead) {
    ++segment_;
  }
  // The carrot: kLookahead ahead of the robot's projection onto the current segment.
  const Point2 a = path_[segment_];
  const Point2 b = path_[segment_ + 1];
  const double len = std::max(distance(a, b), 1e-12);
  const double t = std::clamp(
      ((here.x - a.x) * (b.x - a.x) + (here.y - a.y) * (b.y - a.y)) / (len * len), 0.0, 1.0);
  Point2 from{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
  double left = kLookahead;
  for (std::size_t s = segment_ + 1; s < path_.size(); ++s) {
    const double d = distance(from, path_[s]);
    if (d >= left) {
      const double f = left / d;
      return {from.x + f * (path_[s].x - from.x), from.y + f * (path_[s].y - from.y)};
    }
    left -= d;
    from = path_[s];
  }
  return path_.back();
}

bool Driver::may_enter(const Pose2& next) const {
  const Point2 p{next.x, next.y};
  if (safe_.clear(p)) return true;
  // A robot placed too close to a wall may move, but only through free cells.
  const OccupancyGrid& map = safe_.grid();
  return !safe_.clear(Point2{pose_.x, pose_.y}) &&
         map.at_or(map.world_to_cell(p), CellState::kOccupied) == CellState::kFree;
}

void Driver::advance(double dt) {
  if (path_.size() >= 2 && distance({pose_.x, pose_.y}, path_.back()) < kArrived) {
    ++goals_reached_;
    new_goal();
  }
  if (path_.size() < 2 || stuck_time_ > kGiveUp) {
    stuck_time_ = 0.0;
    new_goal();
    if (path_.size() < 2) return;
  }
  const Point2 target = lookahead_point();
  const double error = wrap_angle(std::atan2(target.y - pose_.y, target.x - pose_.x) - pose_.theta);
  const double w = std::clamp(kTurnGain * error, -config_->max_turn_rate, config_->max_turn_rate);
  const double to_goal = distance({pose_.x, pose_.y}, path_.back());
  double v = std::abs(error) > kTurnInPlace ? 0.0 : config_->speed * std::cos(error);
  v = std::min(v, std::max(0.1, to_goal));  // slow down on the last metre
  Pose2 next = integrate(pose_, v, w, dt);
  if (v > 0.0 && !may_enter(next)) {
    next = integrate(pose_, 0.0, w, dt);
    stuck_time_ += dt;
  }
  pose_ = next;
}

}  // namespace mote::sim::detail
