/// \file
/// Bounds-checked CDR primitives (see cdr.hpp for the rules and their sources).

#include "cdr.hpp"

#include <algorithm>
#include <cstring>

namespace mote::logs::detail {
namespace {

constexpr std::size_t kHeaderBytes = 4;

std::string needs(const char* what, std::size_t n, std::size_t left) {
  return std::string(what) + ": needs " + std::to_string(n) + " bytes, only " +
         std::to_string(left) + " left in the message";
}

}  // namespace

CdrReader::CdrReader(std::string_view message) : bytes_(message) {
  if (message.size() < kHeaderBytes) {
    throw BagDecodeError{0, needs("CDR encapsulation header", kHeaderBytes, message.size())};
  }
  const auto kind = static_cast<unsigned char>(message[1]);
  // 0x00/0x01: plain CDR (XCDR1), big/little endian, what ROS 2 middlewares write. XCDR2 and
  // parameter lists add member headers this decoder does not read, so they are refused.
  if (message[0] != 0 || kind > 0x01) {
    static constexpr std::string_view kHex = "0123456789abcdef";
    throw BagDecodeError{0, "unsupported CDR encapsulation 0x" + std::string(1, kHex[kind >> 4U]) +
                                std::string(1, kHex[kind & 15U]) +
                                ": expected plain CDR (0x00 big endian, 0x01 little endian)"};
  }
  little_ = (kind & 1U) != 0;
}

void CdrReader::align(std::size_t size, const char* what) {
  const std::size_t a = std::min<std::size_t>(size, 8);
  const std::size_t pad = (a - (pos_ - kHeaderBytes) % a) % a;
  if (pad > remaining()) throw BagDecodeError{pos_, needs(what, pad + size, remaining())};
  pos_ += pad;
}

std::uint64_t CdrReader::raw(std::size_t size, const char* what) {
  align(size, what);
  if (size > remaining()) throw BagDecodeError{pos_, needs(what, size, remaining())};
  std::uint64_t v = 0;
  for (std::size_t k = 0; k < size; ++k) {
    const auto byte = static_cast<unsigned char>(bytes_[pos_ + (little_ ? size - 1 - k : k)]);
    v = (v << 8U) | byte;
  }
  pos_ += size;
  return v;
}

std::uint32_t CdrReader::u32(const char* what) { return static_cast<std::uint32_t>(raw(4, what)); }

float CdrReader::f32(const char* what) {
  const auto bits = static_cast<std::uint32_t>(raw(4, what));
  float v = 0.0F;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

double CdrReader::f64(const char* what) {
  const std::uint64_t bits = raw(8, what);
  double v = 0.0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::string_view CdrReader::string(const char* what) {
  const std::size_t at = pos_;
  const std::uint32_t n = u32(what);
  if (n > remaining()) {
    throw BagDecodeError{at, std::string(what) + ": string of " + std::to_string(n) +
                                 " bytes runs past the end of the message (" +
                                 std::to_string(remaining()) + " left)"};
  }
  if (n == 0 || bytes_[pos_ + n - 1] != '\0') {
    throw BagDecodeError{at, std::string(what) + ": string lacks its terminating NUL"};
  }
  const std::string_view out = bytes_.substr(pos_, n - 1);
  pos_ += n;
  return out;
}

std::uint32_t CdrReader::sequence(const char* what, std::size_t min_element_bytes) {
  const std::size_t at = pos_;
  const std::uint32_t n = u32(what);
  if (min_element_bytes > 0 && n > remaining() / min_element_bytes) {
    throw BagDecodeError{at, std::string(what) + ": " + std::to_string(n) +
                                 " elements run past the end of the message (" +
                                 std::to_string(remaining()) + " bytes left)"};
  }
  return n;
}

void CdrReader::skip(std::size_t n, std::size_t size, const char* what) {
  if (n == 0) return;
  align(size, what);
  if (n > remaining() / size) throw BagDecodeError{pos_, needs(what, n * size, remaining())};
  pos_ += n * size;
}

void CdrReader::expect_end(const char* type) const {
  if (remaining() > 3) {
    throw BagDecodeError{pos_, std::string(type) + " has " + std::to_string(remaining()) +
                                   " bytes after its last field"};
  }
}

}  // namespace mote::logs::detail
