// PNG output via libpng's simplified write API (png_image_write_to_file, libpng 1.6).
#include <png.h>

#include "mote/core/error.hpp"
#include "mote/maps/rgb_image.hpp"

namespace mote {

void write_png(const std::filesystem::path& path, const RgbImage& image) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  const int ok =
      png_image_write_to_file(&png, path.c_str(), 0, image.rgb.data(), image.width * 3, nullptr);
  if (ok == 0) throw Error(path.string() + ": cannot write PNG: " + png.message);
}

}  // namespace mote
