// map_server's pixel rules (ros-planning/navigation map_server/src/image_loader.cpp,
// loadMapFromFile) and the amcl reading of the resulting values (amcl_node.cpp convertMap).
#include "mote/maps/map_loader.hpp"

#include <fstream>
#include <string>
#include <vector>

#include "image_readers.hpp"
#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"
#include "mote/core/parallel.hpp"

namespace mote {

namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!std::filesystem::is_regular_file(path) || !in) {
    throw InputError(path.string(), "", "cannot open map image");
  }
  const auto size = static_cast<std::size_t>(in.tellg());
  std::string bytes;
  huge_pages::reserve(bytes, size);
  bytes.resize(size);
  in.seekg(0);
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    throw InputError(path.string(), "", "cannot read map image");
  }
  return bytes;
}

/// amcl's reading of a map_server value: 0 free, 100 occupied, everything else unknown.
CellState state_of(int value) noexcept {
  if (value == 0) return CellState::kFree;
  if (value == 100) return CellState::kOccupied;
  return CellState::kUnknown;
}

/// For one-channel images every pixel value maps through a table of maxval + 1 states.
std::vector<CellState> gray_table(const MapImage& image, const MapMetadata& meta) {
  std::vector<CellState> table(image.maxval + 1);
  for (std::uint32_t v = 0; v <= image.maxval; ++v) {
    const auto sample = static_cast<std::uint16_t>(v);
    table[v] = state_of(map_server_value(image, &sample, meta));
  }
  return table;
}

void check_image(const MapImage& image, const std::string& source) {
  const auto count =
      static_cast<unsigned long long>(image.width) * static_cast<unsigned long long>(image.height);
  if (image.width <= 0 || image.height <= 0 || count > detail::kMaxCells) {
    throw InputError(source, "image size", "image must have 1..2^32 pixels");
  }
  if (image.channels < 1 || image.channels > 4 || image.maxval == 0 || image.maxval > 65535 ||
      image.samples.size() != count * static_cast<unsigned long long>(image.channels)) {
    throw InputError(source, "image data", "channels, maxval and sample count do not agree");
  }
}

}  // namespace

int map_server_value(const MapImage& image, const std::uint16_t* pixel,
                     const MapMetadata& meta) noexcept {
  const double scale = 255.0 / static_cast<double>(image.maxval);
  // Trinary mode averages alpha in with the colours (a map_server quirk kept by nav2).
  const int avg_channels =
      meta.mode == MapMode::kTrinary || !image.has_alpha() ? image.channels : image.channels - 1;
  double sum = 0.0;
  for (int k = 0; k < avg_channels; ++k) sum += pixel[k];
  double color_avg = sum * scale / avg_channels;
  const double alpha = image.has_alpha() ? pixel[image.channels - 1] * scale : 255.0;
  if (meta.negate) color_avg = 255.0 - color_avg;
  if (meta.mode == MapMode::kRaw) {
    const int value = static_cast<int>(color_avg);
    return value <= 100 ? value : -1;
  }
  const double occ = (255.0 - color_avg) / 255.0;
  if (occ > meta.occupied_thresh) return 100;
  if (occ < meta.free_thresh) return 0;
  if (meta.mode == MapMode::kTrinary || alpha < 1.0) return -1;
  const double ratio = (occ - meta.free_thresh) / (meta.occupied_thresh - meta.free_thresh);
  return static_cast<int>(1.0 + 98.0 * ratio);
}

OccupancyGrid grid_from_image(const MapImage& image, const MapMetadata& meta,
                              const std::string& source) {
  check_image(image, source);
  const auto w = static_cast<std::size_t>(image.width);
  const auto h = static_cast<std::size_t>(image.height);
  const auto ch = static_cast<std::size_t>(image.channels);
  const std::vector<CellState> table = ch == 1 ? gray_table(image, meta) : std::vector<CellState>{};
  std::vector<CellState> cells;
  huge_pages::reserve(cells, w * h);
  cells.resize(w * h);
  // Image row 0 is the top of the map; grid row 0 is the bottom.
  par::for_each_chunk(h, /*grain=*/16, [&](std::size_t row_begin, std::size_t row_end) {
    for (std::size_t row = row_begin; row < row_end; ++row) {
      const std::uint16_t* src = image.samples.data() + row * w * ch;
      CellState* dst = cells.data() + (h - 1 - row) * w;
      for (std::size_t i = 0; i < w; ++i) {
        dst[i] = ch == 1 ? table[src[i]] : state_of(map_server_value(image, src + i * ch, meta));
      }
    }
  });
  return {image.width, image.height, meta.resolution, meta.origin, std::move(cells)};
}

MapImage read_map_image(const std::filesystem::path& image) {
  const std::string bytes = read_bytes(image);
  const std::string name = image.string();
  if (bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) {
    return detail::decode_png(name, bytes);
  }
  if (bytes.size() >= 2 && bytes[0] == 'P') return detail::decode_pnm(name, bytes);
  throw InputError(name, "byte 0", "unknown image format (expected PGM, PPM or PNG)");
}

OccupancyGrid load_map(const std::filesystem::path& yaml) {
  const MapMetadata meta = read_map_metadata(yaml);
  // A wrong `image:` is the YAML's mistake: name the YAML and its key, not only the missing path.
  if (!std::filesystem::is_regular_file(meta.image)) {
    throw InputError(yaml.string(), "key 'image'",
                     "cannot open map image " + meta.image.string() + " (" +
                         (std::filesystem::exists(meta.image) ? "not a file" : "no such file") +
                         "; a relative path is taken from the YAML file's folder)");
  }
  const MapImage image = read_map_image(meta.image);
  return grid_from_image(image, meta, meta.image.string());
}

}  // namespace mote
