// PNG decoding with libpng's simplified API, which reports errors through png_image::message
// instead of longjmp, so no C++ object is ever skipped over.
#include <png.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "image_readers.hpp"
#include "mote/core/error.hpp"

namespace mote::detail {

namespace {

/// Frees the libpng read state on every path out of decode_png.
struct PngImageGuard {
  png_image image{};
  PngImageGuard() { image.version = PNG_IMAGE_VERSION; }
  ~PngImageGuard() { png_image_free(&image); }
  PngImageGuard(const PngImageGuard&) = delete;
  PngImageGuard& operator=(const PngImageGuard&) = delete;
};

/// Deflate expands at most about 1032:1, so a header promising more pixel bytes than that
/// ratio allows from the file's size is a lie; refuse it before allocating.
void check_size_claim(const std::string& file, const png_image& image, std::size_t file_size) {
  const auto row = static_cast<unsigned long long>(PNG_IMAGE_ROW_STRIDE(image)) *
                   PNG_IMAGE_PIXEL_COMPONENT_SIZE(image.format);
  const auto cells = static_cast<unsigned long long>(image.width) * image.height;
  const unsigned long long raw = (row + 1) * image.height;
  if (cells > kMaxCells || raw > 1100ULL * file_size + 65536ULL) {
    throw InputError(file, "byte 16 (IHDR)",
                     "header claims " + std::to_string(image.width) + " x " +
                         std::to_string(image.height) + " pixels, more than " +
                         std::to_string(file_size) + " bytes of PNG data can hold");
  }
}

template <class Sample>
MapImage finish(const std::string& file, png_image& image, int channels, std::uint32_t maxval) {
  std::vector<Sample> buffer(PNG_IMAGE_SIZE(image) / sizeof(Sample));
  if (png_image_finish_read(&image, /*background=*/nullptr, buffer.data(), /*row_stride=*/0,
                            /*colormap=*/nullptr) == 0) {
    throw InputError(file, "PNG data", std::string("cannot decode PNG: ") + image.message);
  }
  MapImage img;
  img.width = static_cast<int>(image.width);
  img.height = static_cast<int>(image.height);
  img.channels = channels;
  img.maxval = maxval;
  img.samples.assign(buffer.begin(), buffer.end());
  return img;
}

}  // namespace

MapImage decode_png(const std::string& file, std::string_view bytes) {
  PngImageGuard guard;
  png_image& image = guard.image;
  if (png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()) == 0) {
    throw InputError(file, "PNG header", std::string("cannot read PNG: ") + image.message);
  }
  // Keep the file's own channels (map_server averages RGB itself, not with luminance weights);
  // palettes are expanded. 16-bit files stay 16-bit and linear, 8-bit files untouched.
  image.format &= ~static_cast<png_uint_32>(PNG_FORMAT_FLAG_COLORMAP);
  const int channels = static_cast<int>(PNG_IMAGE_SAMPLE_CHANNELS(image.format));
  check_size_claim(file, image, bytes.size());
  if ((image.format & PNG_FORMAT_FLAG_LINEAR) != 0) {
    return finish<std::uint16_t>(file, image, channels, 65535);
  }
  return finish<std::uint8_t>(file, image, channels, 255);
}

}  // namespace mote::detail
