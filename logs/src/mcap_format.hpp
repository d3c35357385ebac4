#pragma once
/// \file
/// MCAP at the record level (https://mcap.dev/spec): the magic "\x89MCAP0\r\n" at both ends, then
/// records `opcode (u8), length (u64), content`, little endian; strings and byte arrays carry a
/// u32 length, maps a u32 byte length. Parsers throw BagDecodeError with the offset inside the
/// record content.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "bag_format.hpp"

namespace mote::logs::detail::mcap {

inline constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};
inline constexpr std::size_t kRecordHeader = 9;  ///< opcode + length
inline constexpr std::size_t kFooterContent = 20;

enum class Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kDataEnd = 0x0F,
};

struct Record {
  std::uint8_t op = 0;
  std::uint64_t offset = 0;  ///< of the opcode, in the buffer
  std::string_view content;
};

struct Footer {
  std::uint64_t summary_start = 0;
  std::uint64_t summary_offset_start = 0;
  std::uint32_t summary_crc = 0;
};

struct Schema {
  std::uint16_t id = 0;
  std::string name;
  std::string encoding;
  std::string data;
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;
};

struct Message {
  std::uint16_t channel_id = 0;
  std::uint64_t log_time = 0;  ///< ns
  std::string_view data;
};

struct Chunk {
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;  ///< 0: not computed
  std::string compression;             ///< "", "zstd" or "lz4"
  std::string_view records;
};

struct ChunkIndex {
  std::uint64_t start_time = 0;
  std::uint64_t chunk_offset = 0;  ///< of the chunk record, in the file
  std::uint64_t chunk_length = 0;  ///< of the whole record, opcode and length included
  std::string compression;
};

struct Statistics {
  std::uint64_t message_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

/// Sequential records of a buffer (a chunk's records, the summary section).
class RecordCursor {
 public:
  explicit RecordCursor(std::string_view bytes) : bytes_(bytes) {}
  /// The next record; nullopt at the end; throws when a record runs past the buffer.
  std::optional<Record> next();
  [[nodiscard]] std::size_t position() const noexcept { return pos_; }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

Footer parse_footer(std::string_view content);
Schema parse_schema(std::string_view content);
Channel parse_channel(std::string_view content);
Message parse_message(std::string_view content);
Chunk parse_chunk(std::string_view content);
ChunkIndex parse_chunk_index(std::string_view content);
Statistics parse_statistics(std::string_view content);
/// The data section CRC of a DataEnd record (0: not computed).
std::uint32_t parse_data_end(std::string_view content);

/// Decompresses a chunk's records ("" = none, "zstd", "lz4" frame) to exactly `size` bytes,
/// refusing sizes above `max_size` before allocating; throws BagDecodeError.
std::string decompress(const std::string& compression, std::string_view data, std::uint64_t size,
                       std::uint64_t max_size);

/// CRC-32 (ISO-HDLC, as zlib's crc32), continued from `crc` (0 to start).
std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0);

}  // namespace mote::logs::detail::mcap
