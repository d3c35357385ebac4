#pragma once
/// \file
/// The writing half of logs' CdrReader (logs/src/cdr.hpp): OMG CDR as ROS 2 middlewares put it on
/// the wire, plain CDR (XCDR1) in little endian. A 4-byte encapsulation header, then the fields,
/// each aligned to its own size (8 at most) counted from the end of that header; strings are a
/// uint32 length that includes the NUL, then the characters; sequences a uint32 count, then the
/// elements. The finished message is padded to a multiple of 4 bytes, as DDSI requires of a
/// serialized payload.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace mote::ros::detail {

class CdrWriter {
 public:
  /// Starts a message with the header for plain CDR, little endian (00 01 00 00).
  CdrWriter();
  /// Reserves room for `bytes` more bytes (a hint; the writer grows as needed).
  void reserve(std::size_t bytes) { out_.reserve(out_.size() + bytes); }

  void u8(std::uint8_t v);
  void i8(std::int8_t v) { u8(static_cast<std::uint8_t>(v)); }
  void u32(std::uint32_t v);
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f32(float v);
  void f64(double v);
  /// A string: its length with the NUL, the characters, the NUL. Throws ConfigError when it
  /// holds a NUL itself (a CDR string cannot carry one) or is longer than a uint32 counts.
  void string(std::string_view s);
  /// The element count that starts a sequence; throws ConfigError above 2^32 - 1.
  void sequence(std::size_t count);
  /// A fixed-size array of float64 (no count: a Pose's 7 values, a covariance's 36).
  void f64_array(std::span<const double> values);
  /// A sequence of float32: the count, then the elements.
  void f32_sequence(std::span<const float> values);
  /// A sequence of `count` int8 values, element(k) giving the k-th (written in place, without
  /// an intermediate array: a map's cells).
  template <class Element>
  void i8_sequence(std::size_t count, Element&& element) {
    sequence(count);
    const std::size_t first = out_.size();
    out_.resize(first + count);
    char* out = out_.data() + first;
    for (std::size_t k = 0; k < count; ++k) {
      out[k] = static_cast<char>(static_cast<std::int8_t>(element(k)));
    }
  }

  /// Bytes written so far, header included.
  [[nodiscard]] std::size_t size() const noexcept { return out_.size(); }
  /// The message, padded with zeros to a multiple of 4 bytes; the number of padding bytes goes
  /// into the low two bits of the header's options (DDS-XTypes 1.3, 7.6.3.1.2), as Cyclone DDS
  /// writes it. Readers of plain CDR ignore the options, so rmw_cyclonedds's zero there and this
  /// count decode alike.
  [[nodiscard]] std::string finish() &&;

 private:
  void align(std::size_t size);
  void raw(std::uint64_t bits, std::size_t size);
  /// Elements of `size` bytes each, aligned to `size`, in one append where the host is little
  /// endian (a 100k-particle cloud is 6.4 MB).
  template <class T>
  void elements(std::span<const T> values);

  std::string out_;
};

}  // namespace mote::ros::detail
