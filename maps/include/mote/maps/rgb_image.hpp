#pragma once
/// \file
/// An 8-bit RGB picture and its PNG file: what mote's figures (the replay's map.png, the
/// calibration's panels) are drawn into and written as.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace mote {

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

/// Writes an RGB image as PNG. Throws mote::Error naming the file when it cannot be written.
void write_png(const std::filesystem::path& path, const RgbImage& image);

}  // namespace mote
