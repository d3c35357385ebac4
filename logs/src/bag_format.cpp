/// \file
/// ROS bag 2.0 records, headers and chunk decompression (libbz2, LZ4 frame API as roslz4 writes).

#include "bag_format.hpp"

#include <bzlib.h>
#include <lz4frame.h>

#include <cstring>
#include <limits>

#include "mote/core/error.hpp"

namespace mote::logs::detail {

std::string_view ByteReader::take(std::size_t n, const char* what) {
  if (n > remaining()) {
    throw BagDecodeError{pos_, std::string(what) + ": needs " + std::to_string(n) +
                                   " bytes, only " + std::to_string(remaining()) + " left"};
  }
  const std::string_view out = bytes_.substr(pos_, n);
  pos_ += n;
  return out;
}

std::uint32_t ByteReader::u32(const char* what) {
  const std::string_view b = take(4, what);
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8U) | static_cast<unsigned char>(b[static_cast<std::size_t>(i)]);
  return v;
}

std::uint8_t ByteReader::u8(const char* what) {
  return static_cast<unsigned char>(take(1, what)[0]);
}

std::uint16_t ByteReader::u16(const char* what) {
  const std::string_view b = take(2, what);
  return static_cast<std::uint16_t>(
      static_cast<unsigned char>(b[0]) |
      (static_cast<unsigned>(static_cast<unsigned char>(b[1])) << 8U));
}

std::uint64_t ByteReader::u64(const char* what) {
  const std::uint64_t lo = u32(what);
  return lo | (std::uint64_t{u32(what)} << 32U);
}

float ByteReader::f32(const char* what) {
  const std::uint32_t bits = u32(what);
  float v = 0.0F;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

double ByteReader::f64(const char* what) {
  const std::uint64_t lo = u32(what);
  const std::uint64_t hi = u32(what);
  const std::uint64_t bits = lo | (hi << 32U);
  double v = 0.0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::uint32_t ByteReader::sequence(const char* what, std::size_t min_element_bytes) {
  const std::size_t at = pos_;
  const std::uint32_t n = u32((std::string(what) + " length").c_str());
  if (min_element_bytes > 0 && n > remaining() / min_element_bytes) {
    throw BagDecodeError{at, std::string(what) + " length exceeds the message"};
  }
  return n;
}

double ByteReader::time(const char* what) {
  const std::uint32_t sec = u32(what);
  const std::uint32_t nsec = u32(what);
  return static_cast<double>(sec) + 1e-9 * static_cast<double>(nsec);
}

BagHeader::BagHeader(std::string_view bytes) {
  ByteReader reader(bytes);
  while (reader.remaining() > 0) {
    const std::size_t at = reader.position();
    const std::string_view field = reader.string("header field");
    const std::size_t eq = field.find('=');
    if (eq == std::string_view::npos) throw BagDecodeError{at, "header field without '='"};
    fields_.emplace(std::string(field.substr(0, eq)), std::string(field.substr(eq + 1)));
  }
}

std::string_view BagHeader::get(const std::string& name) const {
  const auto it = fields_.find(name);
  if (it == fields_.end()) throw BagDecodeError{0, "record header lacks field '" + name + "'"};
  return it->second;
}

BagOp BagHeader::op() const {
  const std::string_view v = get("op");
  if (v.size() != 1) throw BagDecodeError{0, "field 'op' must be 1 byte"};
  return static_cast<BagOp>(static_cast<unsigned char>(v[0]));
}

std::uint32_t BagHeader::u32(const std::string& name) const {
  const std::string_view v = get(name);
  if (v.size() != 4) throw BagDecodeError{0, "field '" + name + "' must be 4 bytes"};
  return ByteReader(v).u32(name.c_str());
}

std::uint64_t BagHeader::u64(const std::string& name) const {
  const std::string_view v = get(name);
  if (v.size() != 8) throw BagDecodeError{0, "field '" + name + "' must be 8 bytes"};
  ByteReader r(v);
  const std::uint64_t lo = r.u32(name.c_str());
  return lo | (std::uint64_t{r.u32(name.c_str())} << 32U);
}

double BagHeader::time(const std::string& name) const {
  const std::string_view v = get(name);
  if (v.size() != 8) throw BagDecodeError{0, "field '" + name + "' must be 8 bytes"};
  return ByteReader(v).time(name.c_str());
}

BagRecord read_record(ByteReader& reader) {
  BagRecord record;
  record.offset = reader.position();
  const std::string_view header = reader.string("record header");
  try {
    record.header = BagHeader(header);
  } catch (BagDecodeError& e) {
    e.offset += record.offset + 4;
    throw;
  }
  record.data = reader.string("record data");
  return record;
}

namespace {

std::string decompress_bz2(std::string_view data, std::size_t size) {
  std::string out(size, '\0');
  auto out_len = static_cast<unsigned int>(size);
  // libbz2 takes non-const pointers but does not write the source.
  const int rc = BZ2_bzBuffToBuffDecompress(out.data(), &out_len, const_cast<char*>(data.data()),
                                            static_cast<unsigned int>(data.size()), 0, 0);
  if (rc != BZ_OK)
    throw BagDecodeError{0, "bz2 chunk does not decompress (code " + std::to_string(rc) + ")"};
  if (out_len != size) throw BagDecodeError{0, "bz2 chunk is shorter than its declared size"};
  return out;
}

std::string decompress_lz4(std::string_view data, std::size_t size) {
  LZ4F_dctx* ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) {
    throw BagDecodeError{0, "cannot create an LZ4 decompression context"};
  }
  std::string out(size, '\0');
  std::size_t written = 0;
  std::size_t consumed = 0;
  std::size_t hint = 1;
  while (hint != 0 && consumed < data.size()) {
    std::size_t dst = size - written;
    std::size_t src = data.size() - consumed;
    hint = LZ4F_decompress(ctx, out.data() + written, &dst, data.data() + consumed, &src, nullptr);
    if (LZ4F_isError(hint) || (dst == 0 && src == 0)) break;
    written += dst;
    consumed += src;
  }
  LZ4F_freeDecompressionContext(ctx);
  if (LZ4F_isError(hint)) {
    throw BagDecodeError{0,
                         std::string("lz4 chunk does not decompress: ") + LZ4F_getErrorName(hint)};
  }
  if (hint != 0 || written != size) {
    throw BagDecodeError{0, "lz4 chunk does not match its declared size"};
  }
  return out;
}

}  // namespace

std::string decompress_chunk(std::string_view compression, std::string_view data,
                             std::uint64_t size, std::uint64_t max_size) {
  if (size > max_size || size > std::numeric_limits<unsigned int>::max()) {
    throw BagDecodeError{0, "chunk declares " + std::to_string(size) +
                                " bytes, more than the limit of " + std::to_string(max_size)};
  }
  const auto n = static_cast<std::size_t>(size);
  if (compression == "none") {
    if (data.size() != n) throw BagDecodeError{0, "uncompressed chunk size mismatch"};
    return std::string(data);
  }
  if (compression == "bz2") return decompress_bz2(data, n);
  if (compression == "lz4") return decompress_lz4(data, n);
  throw BagDecodeError{0, "unknown chunk compression '" + std::string(compression) + "'"};
}

BagFile::BagFile(const std::string& path)
    : path_(path), file_(std::fopen(path.c_str(), "rb"), &std::fclose) {
  if (!file_) throw InputError(path_, "", "cannot open file");
  std::fseek(file_.get(), 0, SEEK_END);
  const long end = std::ftell(file_.get());
  std::fseek(file_.get(), 0, SEEK_SET);
  if (end < 0) throw InputError(path_, "", "cannot determine the file size");
  size_ = static_cast<std::uint64_t>(end);
  static constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
  char magic[kMagic.size()];
  if (size_ < kMagic.size() || std::fread(magic, 1, kMagic.size(), file_.get()) != kMagic.size() ||
      std::string_view(magic, kMagic.size()) != kMagic) {
    throw InputError(path_, "byte 0", "expected the ROS bag 2.0 magic '#ROSBAG V2.0'");
  }
  pos_ = kMagic.size();
}

void BagFile::read_exact(char* out, std::size_t n, const char* what) {
  if (n > size_ - pos_) {
    throw BagDecodeError{pos_, std::string(what) + ": needs " + std::to_string(n) +
                                   " bytes, only " + std::to_string(size_ - pos_) +
                                   " left in the file"};
  }
  if (std::fread(out, 1, n, file_.get()) != n) throw BagDecodeError{pos_, "read error"};
  pos_ += n;
}

std::uint32_t BagFile::read_u32(const char* what) {
  char b[4];
  read_exact(b, 4, what);
  return ByteReader(std::string_view(b, 4)).u32(what);
}

std::optional<BagRecord> BagFile::next() {
  if (pos_ >= size_) return std::nullopt;
  BagRecord record;
  record.offset = pos_;
  const std::uint32_t header_len = read_u32("record header length");
  if (header_len > size_ - pos_) read_exact(nullptr, header_len, "record header");  // throws
  header_buffer_.resize(header_len);
  read_exact(header_buffer_.data(), header_buffer_.size(), "record header");
  try {
    record.header = BagHeader(header_buffer_);
  } catch (BagDecodeError& e) {
    e.offset += record.offset + 4;
    throw;
  }
  const std::uint32_t data_len = read_u32("record data length");
  if (data_len > size_ - pos_) read_exact(nullptr, data_len, "record data");
  data_buffer_.resize(data_len);
  read_exact(data_buffer_.data(), data_len, "record data");
  record.data = data_buffer_;
  return record;
}

void BagFile::seek(std::uint64_t offset) {
  if (offset > size_ || std::fseek(file_.get(), static_cast<long>(offset), SEEK_SET) != 0) {
    throw BagDecodeError{offset, "seek past the end of the file"};
  }
  pos_ = offset;
}

}  // namespace mote::logs::detail
