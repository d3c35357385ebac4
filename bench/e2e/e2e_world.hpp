#pragma once
/// \file
/// What the end-to-end benchmark drives the Localizer through: a real map (Intel from
/// ../shared/data, else the bundled floor plan), a simulated drive through its free space and
/// the scans taken along it at every beam count the suite uses. Built once per process, outside
/// every timed loop.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote::bench {

/// Beam counts of the suite; the world holds one scan per frame for each.
inline constexpr int kBeamCounts[] = {30, 60, 180};

/// One simulated drive and its scans.
struct World {
  std::string map_name;                         ///< which map the suite ran on
  OccupancyGrid map;                            ///< the map the filters localize on
  std::vector<Pose2> truth;                     ///< true base pose per frame (m, rad)
  std::vector<Pose2> odometry;                  ///< drifting odometry per frame (m, rad)
  std::map<int, std::vector<LaserScan>> scans;  ///< beam count -> one scan per frame

  /// The frame of update k: the drive forward, then back over the same poses, and again, so the
  /// robot never jumps however many updates a benchmark runs.
  [[nodiscard]] std::size_t frame(std::uint64_t k) const noexcept;
  /// The scan of `frame` with `beams` beams (one of kBeamCounts).
  [[nodiscard]] const LaserScan& scan(int beams, std::size_t frame) const;
};

/// The shared world, simulated on first use.
[[nodiscard]] const World& world();

/// `scan` reduced to its middle beam: enough for the filter's first update after an
/// initialization, which only weighs (no motion, no resampling) and is not timed.
[[nodiscard]] LaserScan middle_beam(const LaserScan& scan);

}  // namespace mote::bench
