#pragma once
/// \file
/// map.png: the occupancy grid (free white, occupied black, unknown grey) cropped to the region
/// of interest and scaled up when the map is small, with the reference trajectory (wide, light
/// green, under), the estimated trajectory (thin red on top, orange where the filter was lost),
/// the final particles (blue dots), the start (ring) and end (square); the estimate before the
/// filter settled as separate dots (a global start's estimates jump between places); around it
/// axes in metres, and below a legend and a scale bar.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/engine/localization_state.hpp"
#include "mote/logs/tum.hpp"
#include "mote/maps/figure.hpp"
#include "mote/maps/occupancy_grid.hpp"
#include "mote/maps/rgb_image.hpp"

namespace mote::replay {

/// What is drawn over the map, all in the map frame.
struct MapOverlay {
  std::span<const logs::StampedPose> reference;  ///< drawn as a wide light green polyline
  std::span<const logs::StampedPose> estimate;   ///< drawn as a thin red polyline
  std::span<const Pose2> particles;              ///< drawn as blue dots
  /// The localization state after each estimate pose's update (empty, or one per estimate pose):
  /// segments ending at a lost update are drawn orange.
  std::span<const LocalizationState> states;
  /// Estimate poses before this index are drawn as separate dots, not joined: before the filter
  /// settles its estimate jumps between places, and a line between them would cross walls.
  std::size_t settled = 0;
  /// Where the start marker goes (nullopt: the estimate's first pose) and its legend label.
  std::optional<Pose2> start{};
  std::string start_label = "start";
};

/// Rendering choices.
struct MapRenderOptions {
  double margin_m = 3.0;    ///< m around the trajectories' bounding box kept by the crop
  int target_pixels = 800;  ///< small crops are scaled up by an integer factor towards this
  int max_scale = 8;        ///< largest integer scale factor
};

/// The picture, and where in it the map's cells are.
struct MapFigure {
  RgbImage image;
  figure::PlotArea map_area;  ///< pixels of the cropped grid, `scale` pixels per cell
  int scale = 1;
};

/// Draws the map, the overlay, the axes and the legend. The crop is the bounding box of both
/// trajectories plus the margin (the whole map when there are none), clamped to the map.
[[nodiscard]] MapFigure render_map(const OccupancyGrid& map, const MapOverlay& overlay,
                                   const MapRenderOptions& options = {});

/// render_map then write_png.
void write_map_png(const std::filesystem::path& path, const OccupancyGrid& map,
                   const MapOverlay& overlay, const MapRenderOptions& options = {});

}  // namespace mote::replay
