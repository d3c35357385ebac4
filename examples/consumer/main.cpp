// Uses an installed mote through find_package(mote), compiled with no -march flag: builds a
// small map, runs a job on mote's thread pool and tracks a robot driving through a room with the
// Localizer (motion and likelihood-field kernels, in whichever variant mote dispatched to).
// Exits non-zero when anything is off.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Core>
#include <mote/engine/executor.hpp>
#include <mote/engine/isa.hpp>
#include <mote/engine/localizer.hpp>
#include <mote/maps/occupancy_grid.hpp>

namespace {

// A 4 m x 4 m room of 0.1 m cells with a one-cell wall around it.
mote::OccupancyGrid room() {
  constexpr int kCells = 40;
  std::vector<mote::CellState> cells(kCells * kCells, mote::CellState::kFree);
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i < kCells; ++i) {
      if (i == 0 || j == 0 || i == kCells - 1 || j == kCells - 1) {
        cells[static_cast<std::size_t>(j * kCells + i)] = mote::CellState::kOccupied;
      }
    }
  }
  return {kCells, kCells, 0.1, mote::Pose2{0.0, 0.0, 0.0}, std::move(cells)};
}

// 90 beams from pose p to the inner faces of the walls (x and y in [0.1, 3.9]).
mote::LaserScan scan_from(const mote::Pose2& p) {
  mote::LaserScan scan;
  scan.angle_min = -3.1F;
  scan.angle_increment = 6.2F / 90.0F;
  scan.range_max = 10.0F;
  for (int b = 0; b < 90; ++b) {
    const double a = p.theta + scan.beam_angle(static_cast<std::size_t>(b));
    const double c = std::cos(a);
    const double s = std::sin(a);
    double r = 1e9;
    if (c > 1e-9) r = std::min(r, (3.9 - p.x) / c);
    if (c < -1e-9) r = std::min(r, (0.1 - p.x) / c);
    if (s > 1e-9) r = std::min(r, (3.9 - p.y) / s);
    if (s < -1e-9) r = std::min(r, (0.1 - p.y) / s);
    scan.ranges.push_back(static_cast<float>(r));
  }
  return scan;
}

}  // namespace

int main() {
  const mote::OccupancyGrid grid = room();
  const mote::Executor executor(2);
  const std::size_t free_cells = executor([&] { return grid.free_cell_count(); });
  std::printf("consumer: %zu free cells on %d threads\n", free_cells, executor.threads());
  std::printf("consumer: kernels %s\n", mote::isa_description().c_str());

  mote::LocalizerConfig config;
  config.min_particles = config.max_particles = 2000;
  config.threads = 2;
  config.update_min_d = config.update_min_a = 0.0;
  mote::Localizer localizer(grid, config);
  mote::Pose2 truth{1.5, 1.6, 0.3};
  localizer.initialize(truth, Eigen::Vector3d(0.05, 0.05, 0.02).asDiagonal());
  int updated = 0;
  for (int k = 0; k < 20; ++k) {
    truth.x += 0.05;
    truth.y += 0.02;
    if (localizer.update(truth, scan_from(truth))) ++updated;
  }
  const mote::Pose2 best = localizer.estimate().best().mean;
  const double error = std::hypot(best.x - truth.x, best.y - truth.y);
  std::printf("consumer: %d updates, position error %.3f m\n", updated, error);
  return free_cells == (40 - 2) * (40 - 2) && updated >= 19 && error < 0.1 ? 0 : 1;
}
