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
#include "mote/maps/occupancy_grid.hpp"
#include "mote/replay/tum.hpp"

namespace mote::replay {

/// What is drawn over the map, all in the map frame.
struct MapOverlay {
  std::span<const StampedPose> reference;  ///< drawn as a green polyline
  std::span<const StampedPose> estimate;   ///< drawn as a red polyline
  std::span<const Pose2> particles;        ///< drawn as blue dots
};

/// Rendering choices.
struct MapRenderOptions {
  double margin_m = 3.0;    ///< m around the trajectories' bounding box kept by the crop
  int target_pixels = 800;  ///< small crops are scaled up by an integer factor towards this
  int max_scale = 8;        ///< largest integer scale factor
};

/// An 8-bit RGB image, row 0 at the top.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< width * height * 3
  /// Pointer to the pixel at column x, row y (inside the image).
  [[nodiscard]] std::uint8_t* at(int x, int y) noexcept {
    return rgb.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(x)) *
                            3U;
  }
};

/// Draws the map and the overlay. The crop is the bounding box of both trajectories plus the
/// margin (the whole map when there are none), clamped to the map.
[[nodiscard]] RgbImage render_map(const OccupancyGrid& map, const MapOverlay& overlay,
                                  const MapRenderOptions& options = {});

/// Writes an RGB image as PNG. Throws mote::Error naming the file when it cannot be written.
void write_png(const std::filesystem::path& path, const RgbImage& image);

/// render_map then write_png.
void write_map_png(const std::filesystem::path& path, const OccupancyGrid& map,
                   const MapOverlay& overlay, const MapRenderOptions& options = {});

}  // namespace mote::replay
