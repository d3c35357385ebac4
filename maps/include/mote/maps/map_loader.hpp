#pragma once
/// \file
/// Loading ROS map_server maps: a YAML file (image, resolution, origin, negate, occupied_thresh,
/// free_thresh, mode) and a PGM (P2/P5, maxval up to 65535) or PNG image. Cells are classified
/// with map_server's rules (ros-planning/navigation map_server/src/image_loader.cpp), then read
/// the way amcl reads the published grid: 0 is free, 100 occupied, anything else unknown.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// map_server's `mode` key: how a pixel's occupancy becomes a cell value.
enum class MapMode : std::uint8_t {
  kTrinary,  ///< occupied / free / unknown by the thresholds (the default)
  kScale,    ///< like trinary, but in-between pixels keep a graded value (unknown to amcl)
  kRaw,      ///< the pixel value is the cell value: 0..100, anything else unknown
};

/// The keys of a map_server YAML file.
struct MapMetadata {
  std::filesystem::path image;    ///< image file, resolved against the YAML's folder
  double resolution = 0.0;        ///< m per cell, > 0
  Pose2 origin;                   ///< pose of the lower-left pixel in the map frame (m, rad)
  bool negate = false;            ///< true: white is occupied
  double occupied_thresh = 0.65;  ///< occupancy above this is occupied, in [0, 1]
  double free_thresh = 0.196;     ///< occupancy below this is free, in [0, 1], < occupied_thresh
  MapMode mode = MapMode::kTrinary;
};

/// A decoded image, row 0 at the top as stored in the file.
struct MapImage {
  int width = 0;
  int height = 0;
  int channels = 1;                    ///< 1 gray, 2 gray+alpha, 3 RGB, 4 RGBA
  std::uint32_t maxval = 255;          ///< largest sample value (255 for 8-bit, up to 65535)
  std::vector<std::uint16_t> samples;  ///< width * height * channels, interleaved, row-major
  [[nodiscard]] bool has_alpha() const noexcept { return channels == 2 || channels == 4; }
};

/// Reads and checks a map_server YAML file (the image is not opened).
/// Throws InputError naming the file, the key and the problem.
[[nodiscard]] MapMetadata read_map_metadata(const std::filesystem::path& yaml);

/// Reads a PGM (P2 or P5) or PNG image, chosen by its magic bytes.
/// Throws InputError naming the file, the byte offset or header field and the problem.
[[nodiscard]] MapImage read_map_image(const std::filesystem::path& image);

/// Classifies an in-memory image into a grid with map_server's rules (row 0 of the image is the
/// top row of the map). `source` names the image in error messages.
[[nodiscard]] OccupancyGrid grid_from_image(const MapImage& image, const MapMetadata& meta,
                                            const std::string& source = "image");

/// The map_server cell value of one pixel (-1 unknown, 0 free, 100 occupied, 1..99 graded in
/// scale mode, 0..100 in raw mode); `pixel` points at its `image.channels` samples.
[[nodiscard]] int map_server_value(const MapImage& image, const std::uint16_t* pixel,
                                   const MapMetadata& meta) noexcept;

/// Loads a map_server map: YAML, then its image, then the grid.
[[nodiscard]] OccupancyGrid load_map(const std::filesystem::path& yaml);

}  // namespace mote
