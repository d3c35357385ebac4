#pragma once
/// \file
/// map.png: the occupancy grid (free white, occupied black, unknown grey) with the reference
/// trajectory (green), the estimated trajectory (red) and a particle cloud (blue dots) drawn in,
/// cropped to the region of interest and scaled up when the map is small.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/logs/tum.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/maps/rgb_image.hpp"

namespace mote::replay {

/// What is drawn over the map, all in the map frame.
struct MapOverlay {
  std::span<const logs::StampedPose> reference;  ///< drawn as a green polyline
  std::span<const logs::StampedPose> estimate;   ///< drawn as a red polyline
  std::span<const Pose2> particles;              ///< drawn as blue dots
};

/// Rendering choices.
struct MapRenderOptions {
  double margin_m = 3.0;    ///< m around the trajectories' bounding box kept by the crop
  int target_pixels = 800;  ///< small crops are scaled up by an integer factor towards this
  int max_scale = 8;        ///< largest integer scale factor
};

/// Draws the map and the overlay. The crop is the bounding box of both trajectories plus the
/// margin (the whole map when there are none), clamped to the map.
[[nodiscard]] RgbImage render_map(const OccupancyGrid& map, const MapOverlay& overlay,
                                  const MapRenderOptions& options = {});

/// render_map then write_png.
void write_map_png(const std::filesystem::path& path, const OccupancyGrid& map,
                   const MapOverlay& overlay, const MapRenderOptions& options = {});

}  // namespace mote::replay
