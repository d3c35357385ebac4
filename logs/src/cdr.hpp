#pragma once
/// \file
/// OMG CDR as ROS 2 (rmw_fastrtps, rmw_cyclonedds) serializes messages: a 4-byte encapsulation
/// header (DDS-XTypes 1.3, section 7.6.3.1.2: byte 1 selects the representation and, by its low
/// bit, little endian), then the fields, each aligned to its own size counted from the end of
/// that header. Strings are a uint32 length that
/// includes the terminating NUL, then the characters; sequences a uint32 count, then the
/// elements. Every read is bounds-checked and throws BagDecodeError with the message offset.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "bag_format.hpp"

namespace mote::logs::detail {

class CdrReader {
 public:
  /// Reads the encapsulation header; throws BagDecodeError for a short message or a
  /// representation other than plain CDR (either byte order).
  explicit CdrReader(std::string_view message);

  [[nodiscard]] bool little_endian() const noexcept { return little_; }
  /// Offset in the whole message, encapsulation header included.
  [[nodiscard]] std::size_t position() const noexcept { return pos_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return bytes_.size() - pos_; }

  std::uint32_t u32(const char* what);
  std::int32_t i32(const char* what) { return static_cast<std::int32_t>(u32(what)); }
  float f32(const char* what);
  double f64(const char* what);
  /// A string; throws when its length runs past the message or it lacks its NUL.
  std::string_view string(const char* what);
  /// The element count of a sequence whose elements take at least `min_element_bytes` each;
  /// throws when that many elements cannot fit in the rest of the message.
  std::uint32_t sequence(const char* what, std::size_t min_element_bytes);
  /// Skips `n` elements of `size` bytes each (aligned to `size`).
  void skip(std::size_t n, std::size_t size, const char* what);
  /// Throws unless the message is used up (up to 3 bytes of final padding are allowed).
  void expect_end(const char* type) const;

 private:
  void align(std::size_t size, const char* what);
  std::uint64_t raw(std::size_t size, const char* what);

  std::string_view bytes_;
  std::size_t pos_ = 4;
  bool little_ = true;
};

}  // namespace mote::logs::detail
