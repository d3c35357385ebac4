// PNG decoding with libpng's classic API and no colour management: map_server (SDL_image)
// reads the stored sample values as they are, so gAMA/sRGB/iCCP chunks must not change them
// (libpng's simplified API would convert to sRGB). libpng reports errors by longjmp, so every
// setjmp sits in a small function whose frame holds no C++ object with a destructor.
#include <png.h>

#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "image_readers.hpp"
#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"

namespace mote::detail {

namespace {

/// The bytes being decoded and the last libpng error, shared with libpng's callbacks.
struct PngSource {
  const unsigned char* data;
  std::size_t size;
  std::size_t pos;
  char message[256];
};

void on_error(png_structp png, png_const_charp msg) {
  auto* src = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(src->message, sizeof(src->message), "%s (near byte %zu)", msg, src->pos);
  png_longjmp(png, 1);
}

void on_warning(png_structp /*png*/, png_const_charp /*msg*/) {}

void on_read(png_structp png, png_bytep out, png_size_t length) {
  auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (src->size - src->pos < length) png_error(png, "truncated PNG data");
  std::memcpy(out, src->data + src->pos, length);
  src->pos += length;
}

/// Reads the header and sets the transforms: palettes to RGB, low-bit gray to 8 bits,
/// tRNS to an alpha channel. No gamma handling. Returns false on a libpng error.
bool read_header(png_structp png, png_infop info) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_read_info(png, info);
  png_set_expand(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return true;
}

bool read_rows(png_structp png, png_infop info, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

/// Owns the libpng read structures.
struct PngReader {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngReader() { png_destroy_read_struct(&png, &info, nullptr); }
};

/// Deflate expands at most about 1032:1, so a header promising more pixel bytes than that
/// ratio allows from the file's size is a lie; refuse it before allocating.
void check_size_claim(const std::string& file, std::uint32_t w, std::uint32_t h,
                      std::size_t row_bytes, std::size_t file_size) {
  const auto cells = static_cast<unsigned long long>(w) * h;
  const unsigned long long raw = (row_bytes + 1ULL) * h;
  if (cells > kMaxCells || raw > 1100ULL * file_size + 65536ULL) {
    throw InputError(file, "byte 16 (IHDR)",
                     "header claims " + std::to_string(w) + " x " + std::to_string(h) +
                         " pixels, more than " + std::to_string(file_size) +
                         " bytes of PNG data can hold");
  }
}

/// libpng allocates an ancillary chunk whole before reading it, at whatever size its length
/// field claims (1.6 GB from a 6 KB file, a fuzzer finding), so each one's claim is checked
/// against the bytes that remain first. Critical chunks are libpng's to check: IHDR and PLTE
/// have fixed limits, image data is streamed.
void check_ancillary_lengths(const std::string& file, std::string_view bytes) {
  constexpr std::size_t kSignature = 8, kHeader = 8, kCrc = 4;
  std::size_t at = kSignature;
  while (bytes.size() - at >= kHeader) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
    const std::uint64_t length = std::uint64_t{p[0]} << 24 | std::uint64_t{p[1]} << 16 |
                                 std::uint64_t{p[2]} << 8 | std::uint64_t{p[3]};
    const std::string type(bytes.substr(at + 4, 4));
    const std::size_t remain = bytes.size() - at - kHeader;
    const bool ancillary = (p[4] & 0x20) != 0;  // lower-case first letter (PNG spec 5.4)
    if (ancillary && length + kCrc > remain) {
      throw InputError(file, "byte " + std::to_string(at) + " (" + type + " chunk)",
                       type + " chunk claims " + std::to_string(length) + " bytes, only " +
                           std::to_string(remain) + " remain in the file");
    }
    if (type == "IEND" || length + kCrc > remain) return;
    at += kHeader + length + kCrc;
  }
}

MapImage to_samples(const std::vector<unsigned char>& pixels, std::uint32_t w, std::uint32_t h,
                    int channels, int depth) {
  MapImage img;
  img.width = static_cast<int>(w);
  img.height = static_cast<int>(h);
  img.channels = channels;
  img.maxval = depth == 16 ? 65535 : 255;
  const std::size_t count = static_cast<std::size_t>(w) * h * static_cast<std::size_t>(channels);
  huge_pages::reserve(img.samples, count);
  img.samples.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    // 16-bit PNG samples are big-endian.
    img.samples[k] = depth == 16
                         ? static_cast<std::uint16_t>(pixels[2 * k] << 8 | pixels[2 * k + 1])
                         : pixels[k];
  }
  return img;
}

}  // namespace

MapImage decode_png(const std::string& file, std::string_view bytes) {
  check_ancillary_lengths(file, bytes);
  PngSource src{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 0, {}};
  PngReader r;
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, on_error, on_warning);
  if (r.png != nullptr) r.info = png_create_info_struct(r.png);
  if (r.info == nullptr) throw InputError(file, "", "out of memory creating the PNG reader");
  png_set_read_fn(r.png, &src, on_read);
  if (!read_header(r.png, r.info)) {
    throw InputError(file, "PNG header", std::string("cannot read PNG: ") + src.message);
  }
  const std::uint32_t w = png_get_image_width(r.png, r.info);
  const std::uint32_t h = png_get_image_height(r.png, r.info);
  const std::size_t row_bytes = png_get_rowbytes(r.png, r.info);
  check_size_claim(file, w, h, row_bytes, bytes.size());
  std::vector<unsigned char> pixels(row_bytes * h);
  std::vector<png_bytep> rows(h);
  for (std::size_t j = 0; j < h; ++j) rows[j] = pixels.data() + j * row_bytes;
  if (!read_rows(r.png, r.info, rows.data())) {
    throw InputError(file, "PNG data", std::string("cannot decode PNG: ") + src.message);
  }
  return to_samples(pixels, w, h, png_get_channels(r.png, r.info),
                    png_get_bit_depth(r.png, r.info));
}

}  // namespace mote::detail
