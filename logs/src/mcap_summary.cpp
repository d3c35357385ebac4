/// \file
/// MCAP footer and summary section.

#include "mcap_summary.hpp"

#include <algorithm>

namespace mote::logs::detail::mcap {
namespace {

void check_crc(McapFile& file, const Footer& f, std::uint64_t footer_at) {
  if (f.summary_crc == 0) return;
  // The CRC covers the summary section and the footer up to its summary_crc field.
  const std::uint64_t n = footer_at + kRecordHeader + 16 - f.summary_start;
  if (file.crc(f.summary_start, n, 0) != f.summary_crc) {
    throw BagDecodeError{footer_at, "summary CRC mismatch: the summary is corrupt"};
  }
}

void add_chunk_index(Summary& s, const ChunkIndex& c) {
  if (c.chunk_offset < kMagic.size() || c.chunk_offset > s.data_end ||
      c.chunk_length > s.data_end - c.chunk_offset) {
    throw BagDecodeError{0, "chunk index points at bytes " + std::to_string(c.chunk_offset) +
                                " + " + std::to_string(c.chunk_length) +
                                ", outside the data section"};
  }
  s.chunks.push_back(c);
}

void summary_record(Summary& s, const Record& r, std::uint64_t section_at) {
  const auto op = static_cast<Op>(r.op);
  try {
    if (op == Op::kSchema) s.schemas.push_back(parse_schema(r.content));
    if (op == Op::kChannel) s.channels.push_back(parse_channel(r.content));
    if (op == Op::kChunkIndex) add_chunk_index(s, parse_chunk_index(r.content));
    if (op == Op::kStatistics && parse_statistics(r.content).chunk_count == 0) s.unchunked = true;
  } catch (BagDecodeError& e) {
    e.offset += section_at + r.offset + kRecordHeader;
    throw;
  }
}

}  // namespace

Summary read_summary(McapFile& file) {
  Summary s;
  s.data_end = file.size();
  const std::uint64_t tail = kRecordHeader + kFooterContent + kMagic.size();
  if (file.size() < kMagic.size() + tail ||
      file.read(file.size() - kMagic.size(), kMagic.size(), "magic") != kMagic) {
    return s;
  }
  const std::uint64_t footer_at = file.size() - tail;
  const std::string footer = file.read(footer_at, kRecordHeader + kFooterContent, "footer");
  if (static_cast<Op>(footer[0]) != Op::kFooter) {
    throw BagDecodeError{footer_at, "expected the footer record before the closing magic"};
  }
  const Footer f = parse_footer(std::string_view(footer).substr(kRecordHeader));
  s.has_footer = true;
  s.data_end = f.summary_start == 0 ? footer_at : f.summary_start;
  if (f.summary_start == 0) return s;
  if (f.summary_start < kMagic.size() || f.summary_start > footer_at) {
    throw BagDecodeError{
        footer_at, "summary_start " + std::to_string(f.summary_start) + " is outside the file"};
  }
  check_crc(file, f, footer_at);
  s.has_summary = true;
  const std::string section = file.read(f.summary_start, footer_at - f.summary_start, "summary");
  RecordCursor cursor(section);
  try {
    while (const std::optional<Record> r = cursor.next()) summary_record(s, *r, f.summary_start);
  } catch (BagDecodeError& e) {
    if (e.offset < f.summary_start) e.offset += f.summary_start;  // from the cursor
    throw;
  }
  std::stable_sort(s.chunks.begin(), s.chunks.end(), [](const ChunkIndex& a, const ChunkIndex& b) {
    return a.start_time < b.start_time;
  });
  return s;
}

}  // namespace mote::logs::detail::mcap
