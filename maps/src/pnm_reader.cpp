// Netpbm (PGM/PPM) decoding: header tokens with '#' comments, then binary or ASCII samples.
#include <cctype>
#include <cstdint>
#include <string>

#include "image_readers.hpp"
#include "mote/core/error.hpp"
#include "mote/core/huge_pages.hpp"

namespace mote::detail {

namespace {

/// A cursor over the file's bytes that reports errors with the byte offset.
class PnmCursor {
 public:
  PnmCursor(const std::string& file, std::string_view bytes) : file_(file), bytes_(bytes) {}

  [[noreturn]] void fail(std::size_t at, const std::string& problem) const {
    throw InputError(file_, "byte " + std::to_string(at), problem);
  }
  [[nodiscard]] std::size_t pos() const noexcept { return pos_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return bytes_.size() - pos_; }
  [[nodiscard]] unsigned char byte(std::size_t k) const noexcept {
    return static_cast<unsigned char>(bytes_[k]);
  }

  /// Skips whitespace and, in the header only, '#' comments up to the end of the line.
  void skip_space(bool comments) {
    while (pos_ < bytes_.size()) {
      const unsigned char c = byte(pos_);
      if (comments && c == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && bytes_[pos_] != '\r') ++pos_;
      } else if (std::isspace(c) != 0) {
        ++pos_;
      } else {
        return;
      }
    }
  }

  /// Reads an unsigned decimal number no larger than `limit`; `what` names it in errors.
  std::uint64_t number(const char* what, std::uint64_t limit, bool comments) {
    skip_space(comments);
    const std::size_t start = pos_;
    std::uint64_t value = 0;
    while (pos_ < bytes_.size() && std::isdigit(byte(pos_)) != 0) {
      value = value * 10 + (byte(pos_) - '0');
      if (value > limit) fail(start, std::string(what) + " exceeds " + std::to_string(limit));
      ++pos_;
    }
    if (pos_ == start) {
      if (pos_ == bytes_.size()) fail(start, std::string("truncated: expected ") + what);
      fail(start, std::string("expected ") + what + ", found '" + bytes_[pos_] + "'");
    }
    return value;
  }

  /// The single whitespace byte that ends the header of a binary file.
  void end_of_header() {
    if (pos_ >= bytes_.size() || std::isspace(byte(pos_)) == 0) {
      fail(pos_, "expected one whitespace byte after maxval");
    }
    ++pos_;
  }

 private:
  const std::string& file_;
  std::string_view bytes_;
  std::size_t pos_ = 2;  // after the magic number
};

void read_binary(PnmCursor& in, MapImage& img, std::size_t count) {
  const std::size_t width = img.maxval > 255 ? 2 : 1;
  if (in.remaining() < count * width) {
    in.fail(in.pos() + in.remaining(), "truncated pixel data: expected " +
                                           std::to_string(count * width) + " bytes, found " +
                                           std::to_string(in.remaining()));
  }
  huge_pages::reserve(img.samples, count);
  img.samples.resize(count);
  const std::size_t base = in.pos();
  if (width == 1) {
    for (std::size_t k = 0; k < count; ++k) img.samples[k] = in.byte(base + k);
  } else {
    // 16-bit samples are big-endian (netpbm specification).
    for (std::size_t k = 0; k < count; ++k) {
      img.samples[k] =
          static_cast<std::uint16_t>(in.byte(base + 2 * k) << 8 | in.byte(base + 2 * k + 1));
    }
  }
  if (img.maxval == 255) return;
  for (std::size_t k = 0; k < count; ++k) {
    if (img.samples[k] > img.maxval) in.fail(base + k * width, "sample exceeds maxval");
  }
}

void read_ascii(PnmCursor& in, MapImage& img, std::size_t count) {
  // Every ASCII sample takes at least one digit and one separator.
  if (in.remaining() + 1 < 2 * count) {
    in.fail(in.pos() + in.remaining(), "truncated pixel data: " + std::to_string(count) +
                                           " samples cannot fit in " +
                                           std::to_string(in.remaining()) + " bytes");
  }
  img.samples.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    img.samples[k] = static_cast<std::uint16_t>(in.number("a sample", img.maxval, false));
  }
}

}  // namespace

MapImage decode_pnm(const std::string& file, std::string_view bytes) {
  PnmCursor in(file, bytes);
  const char kind = bytes.size() >= 2 ? bytes[1] : '?';
  if (bytes.size() < 2 || bytes[0] != 'P' ||
      (kind != '2' && kind != '3' && kind != '5' && kind != '6')) {
    in.fail(0, "not a PGM/PPM file (expected magic P2, P3, P5 or P6)");
  }
  MapImage img;
  img.channels = kind == '3' || kind == '6' ? 3 : 1;
  img.width = static_cast<int>(in.number("width", 0x7FFFFFFF, true));
  img.height = static_cast<int>(in.number("height", 0x7FFFFFFF, true));
  img.maxval = static_cast<std::uint32_t>(in.number("maxval", 65535, true));
  if (img.width == 0 || img.height == 0) in.fail(3, "zero image width or height");
  if (img.maxval == 0) in.fail(in.pos(), "maxval must be 1..65535");
  const auto cells =
      static_cast<unsigned long long>(img.width) * static_cast<unsigned long long>(img.height);
  if (cells > kMaxCells) in.fail(3, "image of " + std::to_string(cells) + " pixels is too large");
  const std::size_t count =
      static_cast<std::size_t>(cells) * static_cast<std::size_t>(img.channels);
  if (kind == '5' || kind == '6') {
    in.end_of_header();
    read_binary(in, img, count);
  } else {
    read_ascii(in, img, count);
  }
  return img;
}

}  // namespace mote::detail
