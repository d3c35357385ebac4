#pragma once
/// \file
/// ROS 1 bag format 2.0 at the record level (http://wiki.ros.org/Bags/Format/2.0): records are
/// `header_len, header (len-prefixed name=value fields), data_len, data`, little endian.
/// Every length is checked against what is actually there before anything is allocated.

#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace mote::logs::detail {

/// Record opcodes (the `op` header field).
enum class BagOp : std::uint8_t {
  kMessage = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

/// A malformed piece of a bag: `offset` is relative to the buffer being decoded.
struct BagDecodeError {
  std::uint64_t offset;
  std::string problem;
};

/// Little-endian cursor over a byte buffer; throws BagDecodeError past the end.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  [[nodiscard]] std::size_t position() const noexcept { return pos_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return bytes_.size() - pos_; }
  std::string_view take(std::size_t n, const char* what);
  std::uint8_t u8(const char* what);
  std::uint16_t u16(const char* what);
  std::uint32_t u32(const char* what);
  std::uint64_t u64(const char* what);
  float f32(const char* what);
  double f64(const char* what);
  /// A ROS time (uint32 sec, uint32 nsec) in seconds.
  double time(const char* what);
  /// A uint32-length-prefixed string.
  std::string_view string(const char* what) { return take(u32(what), what); }
  /// The element count of a uint32-length-prefixed array whose elements take at least
  /// `min_element_bytes` each; throws when that many cannot fit in the rest of the buffer. With
  /// skip(), the calls CdrReader has too, so that one decoder body reads either format.
  std::uint32_t sequence(const char* what, std::size_t min_element_bytes);
  /// Skips `n` elements of `size` bytes each.
  void skip(std::size_t n, std::size_t size, const char* what) { (void)take(n * size, what); }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

/// The name=value fields of a record header.
class BagHeader {
 public:
  /// Parses header bytes; throws BagDecodeError (offset within `bytes`).
  explicit BagHeader(std::string_view bytes);
  [[nodiscard]] bool has(const std::string& name) const { return fields_.count(name) != 0; }
  /// The raw value; throws BagDecodeError when missing.
  [[nodiscard]] std::string_view get(const std::string& name) const;
  [[nodiscard]] BagOp op() const;
  [[nodiscard]] std::uint32_t u32(const std::string& name) const;
  [[nodiscard]] std::uint64_t u64(const std::string& name) const;
  [[nodiscard]] double time(const std::string& name) const;

 private:
  std::map<std::string, std::string, std::less<>> fields_;
};

/// One record read from a buffer or the file; `data` views into its owner.
struct BagRecord {
  std::uint64_t offset = 0;  ///< of the record start, in the buffer or file
  BagHeader header{{}};
  std::string_view data;
};

/// Reads the record at `reader`'s position (inside a decompressed chunk).
BagRecord read_record(ByteReader& reader);

/// Decompresses a chunk ("none", "bz2", "lz4") of declared size; throws BagDecodeError.
std::string decompress_chunk(std::string_view compression, std::string_view data,
                             std::uint64_t size, std::uint64_t max_size);

/// Sequential reader of the top-level records of a bag file.
class BagFile {
 public:
  /// Opens and checks the "#ROSBAG V2.0\n" magic; throws InputError.
  explicit BagFile(const std::string& path);
  /// The next record, or nullopt at the end of the file; throws BagDecodeError with a file
  /// offset for a truncated record or a length past the end of the file.
  std::optional<BagRecord> next();
  void seek(std::uint64_t offset);
  [[nodiscard]] std::uint64_t position() const noexcept { return pos_; }
  [[nodiscard]] std::uint64_t size() const noexcept { return size_; }

 private:
  std::uint32_t read_u32(const char* what);
  void read_exact(char* out, std::size_t n, const char* what);

  std::string path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
  std::uint64_t size_ = 0;
  std::uint64_t pos_ = 0;
  std::string header_buffer_;
  std::string data_buffer_;
};

}  // namespace mote::logs::detail
