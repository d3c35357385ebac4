/// \file
/// Bounds-checked reads of an MCAP file.

#include "mcap_file.hpp"

#include <algorithm>

#include "mote/core/error.hpp"

namespace mote::logs::detail::mcap {

McapFile::McapFile(const std::string& path)
    : path_(path), file_(std::fopen(path.c_str(), "rb"), &std::fclose) {
  if (!file_) throw InputError(path_, "", "cannot open file");
  std::fseek(file_.get(), 0, SEEK_END);
  const long end = std::ftell(file_.get());
  if (end < 0) throw InputError(path_, "", "cannot determine the file size");
  size_ = static_cast<std::uint64_t>(end);
  std::string magic;
  if (size_ >= kMagic.size()) magic = read(0, kMagic.size(), "magic");
  if (magic != kMagic)
    throw InputError(path_, "byte 0", "expected the MCAP magic '\\x89MCAP0\\r\\n'");
}

std::string McapFile::read(std::uint64_t offset, std::uint64_t n, const char* what) {
  if (offset > size_ || n > size_ - offset) {
    throw BagDecodeError{offset, std::string(what) + ": needs " + std::to_string(n) +
                                     " bytes, the file has " +
                                     std::to_string(size_ - std::min(offset, size_)) + " left"};
  }
  std::string out(static_cast<std::size_t>(n), '\0');
  if (std::fseek(file_.get(), static_cast<long>(offset), SEEK_SET) != 0 ||
      std::fread(out.data(), 1, out.size(), file_.get()) != out.size()) {
    throw BagDecodeError{offset, std::string(what) + ": read error"};
  }
  return out;
}

std::optional<RecordHead> McapFile::head(std::uint64_t offset, std::uint64_t limit) {
  limit = std::min(limit, size_);
  if (offset > limit || limit - offset < kRecordHeader) return std::nullopt;
  const std::string prefix = read(offset, kRecordHeader, "record");  // outlives the reader
  ByteReader r(prefix);
  RecordHead h;
  h.op = r.u8("opcode");
  h.offset = offset;
  h.length = r.u64("length");
  if (h.length > limit - offset - kRecordHeader) return std::nullopt;
  return h;
}

std::uint32_t McapFile::crc(std::uint64_t offset, std::uint64_t n, std::uint32_t crc) {
  constexpr std::uint64_t kPiece = std::uint64_t{1} << 20U;
  for (std::uint64_t done = 0; done < n;) {
    const std::uint64_t piece = std::min(kPiece, n - done);
    crc = crc32(read(offset + done, piece, "record"), crc);
    done += piece;
  }
  return crc;
}

}  // namespace mote::logs::detail::mcap
