/// \file
/// MCAP record parsers (mcap.dev/spec, "Records"), chunk decompression (libzstd, liblz4 frames)
/// and CRC-32.

#include "mcap_format.hpp"

#include <zstd.h>

#include <array>

namespace mote::logs::detail::mcap {
namespace {

std::string str(ByteReader& r, const char* what) { return std::string(r.string(what)); }

/// A map<K, V> is a u32 byte length then its pairs; only the byte length is checked here.
std::string_view map_bytes(ByteReader& r, const char* what) { return r.string(what); }

std::array<std::uint32_t, 256> crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1U) : c >> 1U;
    t[n] = c;
  }
  return t;
}

std::string decompress_zstd(std::string_view data, std::size_t size) {
  std::string out(size, '\0');
  const std::size_t n = ZSTD_decompress(out.data(), size, data.data(), data.size());
  if (ZSTD_isError(n) != 0) {
    throw BagDecodeError{0, std::string("zstd chunk does not decompress: ") + ZSTD_getErrorName(n)};
  }
  if (n != size) throw BagDecodeError{0, "zstd chunk is shorter than its uncompressed_size"};
  return out;
}

}  // namespace

std::optional<Record> RecordCursor::next() {
  if (pos_ >= bytes_.size()) return std::nullopt;
  ByteReader r(bytes_.substr(pos_));
  Record rec;
  rec.offset = pos_;
  rec.op = r.u8("record opcode");
  const std::uint64_t length = r.u64("record length");
  if (length > r.remaining()) {
    throw BagDecodeError{pos_, "record of " + std::to_string(length) +
                                   " bytes runs past the end (" + std::to_string(r.remaining()) +
                                   " left)"};
  }
  rec.content = r.take(static_cast<std::size_t>(length), "record content");
  pos_ += kRecordHeader + static_cast<std::size_t>(length);
  return rec;
}

Footer parse_footer(std::string_view content) {
  ByteReader r(content);
  Footer f;
  f.summary_start = r.u64("footer summary_start");
  f.summary_offset_start = r.u64("footer summary_offset_start");
  f.summary_crc = r.u32("footer summary_crc");
  return f;
}

Schema parse_schema(std::string_view content) {
  ByteReader r(content);
  Schema s;
  s.id = r.u16("schema id");
  s.name = str(r, "schema name");
  s.encoding = str(r, "schema encoding");
  s.data = str(r, "schema data");
  return s;
}

Channel parse_channel(std::string_view content) {
  ByteReader r(content);
  Channel c;
  c.id = r.u16("channel id");
  c.schema_id = r.u16("channel schema_id");
  c.topic = str(r, "channel topic");
  c.message_encoding = str(r, "channel message_encoding");
  (void)map_bytes(r, "channel metadata");
  return c;
}

Message parse_message(std::string_view content) {
  ByteReader r(content);
  Message m;
  m.channel_id = r.u16("message channel_id");
  (void)r.u32("message sequence");
  m.log_time = r.u64("message log_time");
  (void)r.u64("message publish_time");
  m.data = r.take(r.remaining(), "message data");
  return m;
}

Chunk parse_chunk(std::string_view content) {
  ByteReader r(content);
  Chunk c;
  c.start_time = r.u64("chunk message_start_time");
  c.end_time = r.u64("chunk message_end_time");
  c.uncompressed_size = r.u64("chunk uncompressed_size");
  c.uncompressed_crc = r.u32("chunk uncompressed_crc");
  c.compression = str(r, "chunk compression");
  const std::size_t at = r.position();
  const std::uint64_t n = r.u64("chunk records length");
  if (n != r.remaining()) {
    throw BagDecodeError{at, "chunk records length " + std::to_string(n) + " does not match the " +
                                 std::to_string(r.remaining()) + " bytes of the record"};
  }
  c.records = r.take(r.remaining(), "chunk records");
  return c;
}

ChunkIndex parse_chunk_index(std::string_view content) {
  ByteReader r(content);
  ChunkIndex c;
  c.start_time = r.u64("chunk index message_start_time");
  (void)r.u64("chunk index message_end_time");
  c.chunk_offset = r.u64("chunk index chunk_start_offset");
  c.chunk_length = r.u64("chunk index chunk_length");
  (void)map_bytes(r, "chunk index message_index_offsets");
  (void)r.u64("chunk index message_index_length");
  c.compression = str(r, "chunk index compression");
  return c;
}

Statistics parse_statistics(std::string_view content) {
  ByteReader r(content);
  Statistics s;
  s.message_count = r.u64("statistics message_count");
  (void)r.u16("statistics schema_count");
  (void)r.u32("statistics channel_count");
  (void)r.u32("statistics attachment_count");
  (void)r.u32("statistics metadata_count");
  s.chunk_count = r.u32("statistics chunk_count");
  s.start_time = r.u64("statistics message_start_time");
  s.end_time = r.u64("statistics message_end_time");
  ByteReader counts(map_bytes(r, "statistics channel_message_counts"));
  while (counts.remaining() > 0) {
    const std::uint16_t id = counts.u16("channel id");
    s.channel_message_counts[id] = counts.u64("message count");
  }
  return s;
}

std::uint32_t parse_data_end(std::string_view content) {
  ByteReader r(content);
  return r.u32("data end data_section_crc");
}

std::string decompress(const std::string& compression, std::string_view data, std::uint64_t size,
                       std::uint64_t max_size) {
  if (size > max_size) {
    throw BagDecodeError{0, "chunk declares " + std::to_string(size) +
                                " uncompressed bytes, more than the limit of " +
                                std::to_string(max_size)};
  }
  if (compression.empty()) {
    if (data.size() != size) {
      throw BagDecodeError{0, "uncompressed chunk holds " + std::to_string(data.size()) +
                                  " bytes, its header says " + std::to_string(size)};
    }
    return std::string(data);
  }
  if (compression == "zstd") return decompress_zstd(data, static_cast<std::size_t>(size));
  if (compression == "lz4") return decompress_chunk("lz4", data, size, max_size);
  throw BagDecodeError{0, "unknown chunk compression '" + compression + "'"};
}

std::uint32_t crc32(std::string_view bytes, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> table = crc_table();
  crc = ~crc;
  for (const char ch : bytes) {
    crc = table[(crc ^ static_cast<unsigned char>(ch)) & 0xFFU] ^ (crc >> 8U);
  }
  return ~crc;
}

}  // namespace mote::logs::detail::mcap
