/// \file
/// CDR primitives for writing (see cdr_writer.hpp for the rules and their sources).

#include "cdr_writer.hpp"

#include <algorithm>
#include <bit>
#include <limits>

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
  for (std::size_t k = 0; k < size; ++k) {
    out_.push_back(static_cast<char>(static_cast<unsigned char>(bits >> (8U * k))));
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

void CdrWriter::f32_sequence(std::span<const float> values) {
  sequence(values.size());
  reserve(4 * values.size());
  for (const float v : values) f32(v);
}

std::string CdrWriter::finish() && {
  const std::size_t pad = (4 - out_.size() % 4) % 4;
  out_.append(pad, '\0');
  out_[3] = static_cast<char>(pad);
  return std::move(out_);
}

}  // namespace mote::ros::detail
