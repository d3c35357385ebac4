/// \file
/// CDR primitives for writing (see cdr_writer.hpp for the rules and their sources).

#include "cdr_writer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <type_traits>

#include "mote/core/error.hpp"

namespace mote::ros::detail {
namespace {

constexpr std::size_t kHeaderBytes = 4;

std::uint32_t checked_count(std::size_t n, const char* what) {
  if (n > std::numeric_limits<std::uint32_t>::max()) {
    throw ConfigError(std::string("CDR ") + what + " of " + std::to_string(n) +
                      " elements: more than a uint32 count holds");
  }
  return static_cast<std::uint32_t>(n);
}

}  // namespace

// Byte 1 is the representation identifier: 0x01 is CDR_LE (plain CDR, little endian).
CdrWriter::CdrWriter() : out_{'\0', '\x01', '\0', '\0'} {}

void CdrWriter::align(std::size_t size) {
  const std::size_t a = std::min<std::size_t>(size, 8);
  const std::size_t pad = (a - (out_.size() - kHeaderBytes) % a) % a;
  out_.append(pad, '\0');
}

void CdrWriter::raw(std::uint64_t bits, std::size_t size) {
  align(size);
  std::array<char, 8> little{};
  for (std::size_t k = 0; k < size; ++k) {
    little[k] = static_cast<char>(static_cast<unsigned char>(bits >> (8U * k)));
  }
  out_.append(little.data(), size);
}

template <class T>
void CdrWriter::elements(std::span<const T> values) {
  if (values.empty()) return;
  align(sizeof(T));
  if constexpr (std::endian::native == std::endian::little) {
    const std::size_t first = out_.size();
    out_.resize(first + values.size_bytes());
    std::memcpy(out_.data() + first, values.data(), values.size_bytes());
  } else {
    using Bits = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>;
    for (const T v : values) raw(std::bit_cast<Bits>(v), sizeof(T));
  }
}

void CdrWriter::u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
void CdrWriter::u32(std::uint32_t v) { raw(v, 4); }
void CdrWriter::f32(float v) { raw(std::bit_cast<std::uint32_t>(v), 4); }
void CdrWriter::f64(double v) { raw(std::bit_cast<std::uint64_t>(v), 8); }

void CdrWriter::string(std::string_view s) {
  if (s.find('\0') != std::string_view::npos) {
    throw ConfigError("CDR string holds a NUL character: it would end the string early");
  }
  u32(checked_count(s.size() + 1, "string"));
  out_.append(s);
  out_.push_back('\0');
}

void CdrWriter::sequence(std::size_t count) { u32(checked_count(count, "sequence")); }

void CdrWriter::f64_array(std::span<const double> values) { elements(values); }

void CdrWriter::f32_sequence(std::span<const float> values) {
  sequence(values.size());
  elements(values);
}

std::string CdrWriter::finish() && {
  const std::size_t pad = (4 - out_.size() % 4) % 4;
  out_.append(pad, '\0');
  out_[3] = static_cast<char>(pad);
  return std::move(out_);
}

}  // namespace mote::ros::detail
