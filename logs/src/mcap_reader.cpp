/// \file
/// MCAP storage (mcap.dev/spec). With a footer that points at a summary section, schemas and
/// channels come from the summary and chunks are read in the order of their chunk indexes'
/// start times; the summary CRC is checked when the footer carries one. Without a summary (or
/// a file cut short while recording: no footer, no trailing magic) the records are scanned
/// linearly, once for schemas and channels and once for messages, up to the last complete
/// record, with a warning; the Data End record's CRC of the data section is checked then.
/// Messages inside one chunk are handed out in log-time order (stable), chunk CRCs checked.

#include <algorithm>
#include <map>
#include <set>

#include "mcap_summary.hpp"
#include "mote/core/error.hpp"
#include "ros2_storage.hpp"

namespace mote::logs::detail {
namespace {

using mcap::Op;

struct Pending {
  std::uint16_t channel = 0;
  std::uint64_t log_time = 0;
  std::string_view data;
  std::uint64_t offset = 0;  ///< of the message record in its chunk's records, or the file
  std::optional<std::uint64_t> chunk;  ///< file offset of its chunk record
};

class McapStorage final : public Ros2Storage {
 public:
  McapStorage(const std::filesystem::path& path, const ReaderOptions& options)
      : name_(path.string()), options_(options), file_(name_) {
    guarded([&] { use_summary(mcap::read_summary(file_)); });
  }

  [[nodiscard]] const std::string& name() const override { return name_; }
  [[nodiscard]] const std::vector<Ros2Topic>& topics() const override { return topics_; }
  [[nodiscard]] const ReadStats& stats() const override { return stats_; }

  [[nodiscard]] StorageSummary summary() const override {
    std::string compression;
    for (const std::string& c : compressions_) compression += (compression.empty() ? "" : ", ") + c;
    return {"mcap", compression, indexed_ ? "summary and chunk index" : "linear scan"};
  }

  std::optional<Ros2Message> next() override {
    while (next_pending_ == pending_.size()) {
      pending_.clear();
      next_pending_ = 0;
      if (!guarded([&] { return indexed_ ? next_indexed_chunk() : next_linear_records(); })) {
        return std::nullopt;
      }
    }
    const Pending& p = pending_[next_pending_++];
    const auto topic = topic_of_.find(p.channel);
    if (topic == topic_of_.end()) {
      fail(p.offset, "message on channel " + std::to_string(p.channel) + ", which is not defined");
    }
    const std::string where = p.chunk ? "byte " + std::to_string(*p.chunk) + " (chunk), offset " +
                                            std::to_string(p.offset) +
                                            " of its records (message record)"
                                      : "byte " + std::to_string(p.offset) + " (message record)";
    return Ros2Message{topic->second, static_cast<std::int64_t>(p.log_time), p.data, where};
  }

 private:
  [[noreturn]] void fail(std::uint64_t offset, const std::string& problem) const {
    throw InputError(name_, "byte " + std::to_string(offset), problem);
  }

  /// Runs `body`, turning a BagDecodeError (a file offset) into an InputError.
  template <typename Body>
  auto guarded(Body body) -> decltype(body()) {
    try {
      return body();
    } catch (const BagDecodeError& e) {
      fail(e.offset, e.problem);
    }
  }

  /// Schemas and channels from the summary; chunks in its index order when it has a chunk
  /// index, else (or with no summary at all) a linear scan of the data section.
  void use_summary(mcap::Summary summary) {
    data_end_ = summary.data_end;
    has_footer_ = summary.has_footer;
    for (mcap::Schema& schema : summary.schemas) add_schema(std::move(schema));
    for (const mcap::Channel& channel : summary.channels) add_channel(channel);
    chunks_ = std::move(summary.chunks);
    for (const mcap::ChunkIndex& c : chunks_) {
      compressions_.insert(c.compression.empty() ? "none" : c.compression);
    }
    indexed_ = !chunks_.empty();
    if (!indexed_ && !(summary.has_summary && summary.unchunked)) scan_definitions();
  }

  // --- definitions ----------------------------------------------------------------------

  void add_schema(mcap::Schema s) { schemas_[s.id] = std::move(s); }

  void add_channel(const mcap::Channel& c) {
    if (topic_of_.count(c.id) != 0) return;
    Ros2Topic t;
    t.name = c.topic;
    t.encoding = c.message_encoding;
    t.place = "channel id " + std::to_string(c.id);
    const auto s = schemas_.find(c.schema_id);
    if (c.schema_id != 0 && s == schemas_.end()) {
      throw BagDecodeError{0, "channel " + std::to_string(c.id) + " ('" + c.topic +
                                  "') refers to schema " + std::to_string(c.schema_id) +
                                  ", which is not defined before it"};
    }
    if (s != schemas_.end()) {
      t.type = s->second.name;
      t.schema_encoding = s->second.encoding;
      t.schema_text = s->second.data;
      t.place += ", schema id " + std::to_string(c.schema_id);
    }
    topic_of_[c.id] = topics_.size();
    topics_.push_back(std::move(t));
  }

  /// Linear mode, first pass: the schemas and channels, top level and inside chunks.
  void scan_definitions() {
    for (std::uint64_t at = mcap::kMagic.size(); at < data_end_;) {
      const std::optional<mcap::RecordHead> h = file_.head(at, data_end_);
      if (!h || static_cast<Op>(h->op) == Op::kFooter || static_cast<Op>(h->op) == Op::kDataEnd) {
        break;
      }
      const auto op = static_cast<Op>(h->op);
      if (op == Op::kSchema || op == Op::kChannel || op == Op::kChunk) {
        const std::string content = file_.read(at + mcap::kRecordHeader, h->length, "record");
        if (op == Op::kChunk) {
          chunk_definitions(content, at);
        } else {
          definition(op, content, at + mcap::kRecordHeader);
        }
      }
      at = h->end();
    }
  }

  void definition(Op op, std::string_view content, std::uint64_t at) {
    try {
      if (op == Op::kSchema) add_schema(mcap::parse_schema(content));
      if (op == Op::kChannel) add_channel(mcap::parse_channel(content));
    } catch (BagDecodeError& e) {
      e.offset += at;
      throw;
    }
  }

  void chunk_definitions(std::string_view content, std::uint64_t at) {
    try {
      const std::string records = open_chunk(content);
      mcap::RecordCursor cursor(records);
      while (const std::optional<mcap::Record> r = cursor.next()) {
        definition(static_cast<Op>(r->op), r->content, 0);
      }
    } catch (const BagDecodeError& e) {
      if (!options_.lenient) throw InputError(name_, chunk_place(at, e.offset), e.problem);
    }
  }

  // --- messages -------------------------------------------------------------------------

  static std::string chunk_place(std::uint64_t chunk_at, std::uint64_t offset) {
    return "byte " + std::to_string(chunk_at) + " (chunk), offset " + std::to_string(offset) +
           " of its records";
  }

  /// A chunk's records, decompressed and CRC-checked.
  std::string open_chunk(std::string_view content) {
    const mcap::Chunk c = mcap::parse_chunk(content);
    compressions_.insert(c.compression.empty() ? "none" : c.compression);
    std::string records =
        mcap::decompress(c.compression, c.records, c.uncompressed_size, options_.max_chunk_bytes);
    if (c.uncompressed_crc != 0 && mcap::crc32(records) != c.uncompressed_crc) {
      throw BagDecodeError{0, "chunk CRC mismatch: its records are corrupt"};
    }
    return records;
  }

  bool next_indexed_chunk() {
    if (next_chunk_ == chunks_.size()) return false;
    const mcap::ChunkIndex& index = chunks_[next_chunk_++];
    const std::optional<mcap::RecordHead> h = file_.head(index.chunk_offset, data_end_);
    if (!h || static_cast<Op>(h->op) != Op::kChunk ||
        h->length + mcap::kRecordHeader != index.chunk_length) {
      fail(index.chunk_offset, "expected the chunk record of " +
                                   std::to_string(index.chunk_length) +
                                   " bytes that the chunk index places here");
    }
    load_chunk(index.chunk_offset, file_.read(h->offset + 9, h->length, "chunk"));
    return true;
  }

  /// Linear mode: reads records up to the next chunk or message; false at the end.
  bool next_linear_records() {
    while (!linear_done_) {
      const std::optional<mcap::RecordHead> h = file_.head(linear_at_, data_end_);
      if (!h) {
        end_of_records();
        return false;
      }
      const auto op = static_cast<Op>(h->op);
      if (op == Op::kFooter || op == Op::kDataEnd) {
        if (op == Op::kDataEnd) check_data_crc(*h);
        if (!has_footer_)
          warn(h->end(),
               "the file ends after its Data End record without the "
               "footer and closing magic (cut short?)");
        linear_done_ = true;
        return false;
      }
      const std::string content = file_.read(h->offset + 9, h->length, "record");
      data_crc_ = mcap::crc32(content, file_.crc(h->offset, mcap::kRecordHeader, data_crc_));
      linear_at_ = h->end();
      if (op == Op::kChunk) load_chunk(h->offset, content);
      if (op == Op::kMessage) load_message(h->offset, content);
      if (!pending_.empty()) return true;
    }
    return false;
  }

  void end_of_records() {
    linear_done_ = true;
    if (linear_at_ >= data_end_ && data_end_ < file_.size()) return;  // summary follows
    warn(linear_at_,
         "the file ends without its Data End record and footer (cut short while "
         "recording?): read up to here, " +
             std::to_string(file_.size() - linear_at_) + " bytes of an incomplete record ignored");
    stats_.bytes_skipped += file_.size() - linear_at_;
  }

  void warn(std::uint64_t at, const std::string& problem) {
    stats_.warnings.emplace_back(InputError(name_, "byte " + std::to_string(at), problem).what());
  }

  void check_data_crc(const mcap::RecordHead& h) {
    const std::uint32_t want =
        mcap::parse_data_end(file_.read(h.offset + 9, h.length, "data end record"));
    if (want != 0 && want != data_crc_) {
      fail(h.offset, "data section CRC mismatch: the records before this Data End are corrupt");
    }
  }

  void load_message(std::uint64_t at, const std::string& content) {
    chunk_ = content;
    const mcap::Message m = parse_at(at + mcap::kRecordHeader, chunk_);
    pending_.push_back({m.channel_id, m.log_time, m.data, at, std::nullopt});
  }

  static mcap::Message parse_at(std::uint64_t at, std::string_view content) {
    try {
      return mcap::parse_message(content);
    } catch (BagDecodeError& e) {
      e.offset += at;
      throw;
    }
  }

  void load_chunk(std::uint64_t at, const std::string& content) {
    try {
      chunk_ = open_chunk(content);
      chunk_messages(at);
    } catch (const BagDecodeError& e) {
      const std::string where = chunk_place(at, e.offset);
      if (!options_.lenient) throw InputError(name_, where, e.problem);
      pending_.clear();
      ++stats_.records_skipped;
      stats_.bytes_skipped += content.size();
      if (stats_.first_error.empty())
        stats_.first_error = InputError(name_, where, e.problem).what();
    }
  }

  void chunk_messages(std::uint64_t chunk_at) {
    mcap::RecordCursor cursor(chunk_);
    while (const std::optional<mcap::Record> r = cursor.next()) {
      const auto op = static_cast<Op>(r->op);
      if (op == Op::kSchema || op == Op::kChannel) definition(op, r->content, r->offset + 9);
      if (op != Op::kMessage) continue;
      const mcap::Message m = parse_at(r->offset + mcap::kRecordHeader, r->content);
      pending_.push_back({m.channel_id, m.log_time, m.data, r->offset, chunk_at});
    }
    std::stable_sort(pending_.begin(), pending_.end(),
                     [](const Pending& a, const Pending& b) { return a.log_time < b.log_time; });
  }

  std::string name_;
  ReaderOptions options_;
  mcap::McapFile file_;
  ReadStats stats_;
  std::map<std::uint16_t, mcap::Schema> schemas_;
  std::map<std::uint16_t, std::size_t> topic_of_;
  std::vector<Ros2Topic> topics_;
  std::vector<mcap::ChunkIndex> chunks_;
  std::set<std::string> compressions_;
  std::uint64_t data_end_ = 0;  ///< where the data section ends (summary start, footer or EOF)
  bool indexed_ = false;
  bool has_footer_ = false;  ///< the file ends with a footer and the closing magic
  std::size_t next_chunk_ = 0;
  std::uint64_t linear_at_ = mcap::kMagic.size();
  std::uint32_t data_crc_ = mcap::crc32(mcap::kMagic);
  bool linear_done_ = false;
  std::string chunk_;  ///< the current chunk's records (or a top-level message record)
  std::vector<Pending> pending_;
  std::size_t next_pending_ = 0;
};

}  // namespace

std::unique_ptr<Ros2Storage> open_mcap_storage(const std::filesystem::path& path,
                                               const ReaderOptions& options) {
  return std::make_unique<McapStorage>(path, options);
}

}  // namespace mote::logs::detail
