// Uses an installed mote through find_package(mote): builds a small map and runs a job on
// mote's thread pool. Exits non-zero when anything is off.
#include <cstdio>
#include <vector>

#include <mote/engine/executor.hpp>
#include <mote/maps/occupancy_grid.hpp>

int main() {
  std::vector<mote::CellState> cells(4 * 3, mote::CellState::kFree);
  cells[5] = mote::CellState::kOccupied;
  const mote::OccupancyGrid grid(4, 3, 0.5, mote::Pose2{-1.0, -1.0, 0.0}, std::move(cells));
  const mote::Executor executor(2);
  const std::size_t free_cells = executor([&] { return grid.free_cell_count(); });
  std::printf("consumer: %zu free cells on %d threads\n", free_cells, executor.threads());
  return free_cells == 11 ? 0 : 1;
}
