#pragma once
/// \file
/// Random access to an MCAP file's records: every length is checked against the file size (or a
/// caller's limit) before anything is allocated.

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "mcap_format.hpp"

namespace mote::logs::detail::mcap {

/// A top-level record's opcode and content length, read from its 9-byte prefix.
struct RecordHead {
  std::uint8_t op = 0;
  std::uint64_t offset = 0;
  std::uint64_t length = 0;  ///< of the content
  [[nodiscard]] std::uint64_t end() const noexcept { return offset + kRecordHeader + length; }
};

class McapFile {
 public:
  /// Opens `path` and checks the leading magic; throws InputError.
  explicit McapFile(const std::string& path);
  [[nodiscard]] std::uint64_t size() const noexcept { return size_; }
  /// `n` bytes at `offset`; throws BagDecodeError (file offset) past the end of the file.
  std::string read(std::uint64_t offset, std::uint64_t n, const char* what);
  /// The record prefix at `offset`; nullopt when the record does not end by `limit` (a file cut
  /// short, or a length that claims more than there is).
  std::optional<RecordHead> head(std::uint64_t offset, std::uint64_t limit);
  /// CRC-32 of `n` bytes at `offset`, continued from `crc`, read in pieces.
  std::uint32_t crc(std::uint64_t offset, std::uint64_t n, std::uint32_t crc);

 private:
  std::string path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
  std::uint64_t size_ = 0;
};

}  // namespace mote::logs::detail::mcap
