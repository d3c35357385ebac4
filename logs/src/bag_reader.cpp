/// \file
/// ROS 1 bag (format 2.0) scan source. Streams one chunk at a time; within a chunk, messages are
/// sorted by their record time (stable), because chunk order is not guaranteed time order while
/// rosbag writes chunks themselves in time order. Connections are taken from the index at the
/// end of the file when it is there, and from the connection records inside chunks otherwise.

#include <algorithm>
#include <deque>
#include <map>

#include "bag_format.hpp"
#include "bag_messages.hpp"
#include "bag_sync.hpp"
#include "mote/core/error.hpp"
#include "mote/logs/scan_source.hpp"

namespace mote::logs {
namespace {

using detail::BagDecodeError;
using detail::BagOp;
using detail::BagRecord;

enum class Role { kNone, kScan, kOdom, kTf };

struct Event {
  double time;
  std::uint64_t offset;  ///< of the message record inside its chunk
  Role role;
  std::string_view data;
};

class BagSource final : public ScanSource {
 public:
  BagSource(const std::filesystem::path& path, const ReaderOptions& options)
      : name_(path.string()), file_(name_), options_(options), sync_(options.odom_frame) {
    read_bag_header();
  }

  std::optional<ScanFrame> next() override {
    while (ready_.empty() && !finished_) {
      if (read_chunk()) {
        (void)sync_.flush(ready_, false);
      } else {
        finish();
      }
    }
    if (ready_.empty()) {
      // A bag without a single scan that no skipped record explains: empty, cut or wrong topic.
      if (frames_ == 0 && stats_.records_skipped == 0) {
        fail(file_.size(), "end of file without a sensor_msgs/LaserScan message" +
                               (options_.scan_topic.empty() ? std::string()
                                                            : " on '" + options_.scan_topic + "'"));
      }
      return std::nullopt;
    }
    ScanFrame frame = std::move(ready_.front());
    ready_.pop_front();
    ++frames_;
    return frame;
  }

  [[nodiscard]] ReadStats stats() const override { return stats_; }

 private:
  [[noreturn]] void fail(std::uint64_t offset, const std::string& problem) const {
    throw InputError(name_, "byte " + std::to_string(offset), problem);
  }

  /// Strict mode, a record that does not decode: in a bag whose header places the index past
  /// the file's end, or that was never closed (index at 0), the likely cause is a file cut short,
  /// which --lenient reads up to the cut (as the MCAP reader does for a cut file).
  [[noreturn]] void fail_record(std::uint64_t offset, const std::string& problem) const {
    if (index_pos_ != 0 && index_pos_ <= file_.size()) fail(offset, problem);
    fail(offset,
         problem + " (the bag's index " +
             (index_pos_ == 0 ? std::string("was never written")
                              : "lies past its end, at byte " + std::to_string(index_pos_)) +
             ": cut short? --lenient reads the scans before the cut)");
  }

  /// Lenient mode: counts a skipped record; the first one's message reads like an InputError's.
  void skip(std::uint64_t bytes, const std::string& place, const std::string& problem) {
    ++stats_.records_skipped;
    stats_.bytes_skipped += bytes;
    if (stats_.first_error.empty()) stats_.first_error = InputError(name_, place, problem).what();
  }

  /// The end of the records: the file must reach the index its header announces (a bag cut at a
  /// record boundary would otherwise lose its last chunks silently), and pending scans need
  /// odometry.
  void finish() {
    finished_ = true;
    if (index_pos_ > file_.size() && stats_.records_skipped == 0) {
      const std::string problem = "the file ends before byte " + std::to_string(index_pos_) +
                                  ", where its header places the index: the bag is cut short";
      if (!options_.lenient) fail(file_.size(), problem + " (--lenient reads the scans before it)");
      skip(index_pos_ - file_.size(), "byte " + std::to_string(file_.size()), problem);
    }
    if (!sync_.flush(ready_, true)) {
      fail(file_.size(),
           "scans without odometry: no nav_msgs/Odometry topic and no tf "
           "transform from '" +
               options_.odom_frame + "'");
    }
  }

  void read_bag_header() {
    try {
      const std::optional<BagRecord> header = file_.next();
      if (!header || header->header.op() != BagOp::kBagHeader)
        fail(13, "expected the bag header record");
      index_pos_ = header->header.u64("index_pos");
      if (index_pos_ > file_.position() && index_pos_ < file_.size()) read_index(index_pos_);
    } catch (const BagDecodeError& e) {
      fail(e.offset, e.problem);
    }
  }

  /// Connection records from the index section; the index is optional, so a broken one is
  /// ignored and connections are then learned from the chunks.
  void read_index(std::uint64_t index_pos) {
    const std::uint64_t resume = file_.position();
    try {
      file_.seek(index_pos);
      while (const std::optional<BagRecord> r = file_.next()) {
        if (r->header.op() == BagOp::kConnection) add_connection(*r);
      }
    } catch (const BagDecodeError&) {
    }
    file_.seek(resume);
  }

  void add_connection(const BagRecord& r) {
    const std::uint32_t conn = r.header.u32("conn");
    if (roles_.count(conn) != 0) return;
    const std::string topic(r.header.get("topic"));
    const std::string type(detail::BagHeader(r.data).get("type"));
    Role role = Role::kNone;
    if (type == "sensor_msgs/LaserScan" && claim(scan_topic_, options_.scan_topic, topic)) {
      role = Role::kScan;
    } else if (type == "nav_msgs/Odometry" && claim(odom_topic_, options_.odom_topic, topic)) {
      role = Role::kOdom;
      sync_.use_odometry_topic();
    } else if (type == "tf2_msgs/TFMessage" || type == "tf/tfMessage") {
      role = Role::kTf;
    }
    roles_[conn] = role;
  }

  /// True when `topic` is the chosen one: the option, else the first seen.
  static bool claim(std::string& chosen, const std::string& option, const std::string& topic) {
    if (chosen.empty()) chosen = option.empty() ? topic : option;
    return topic == chosen;
  }

  /// Reads records up to and including the next chunk; false at the end of the input.
  bool read_chunk() {
    while (true) {
      std::optional<BagRecord> record;
      try {
        record = file_.next();
        if (!record) return false;
        if (record->header.op() == BagOp::kChunk) {
          process_chunk(*record);
          return true;
        }
        if (record->header.op() == BagOp::kConnection) add_connection(*record);
      } catch (const BagDecodeError& e) {
        const std::uint64_t at = record ? record->offset + e.offset : e.offset;
        if (!options_.lenient) fail_record(at, e.problem);
        const std::uint64_t from = record ? record->offset : e.offset;
        skip(file_.size() - std::min(from, file_.size()), "byte " + std::to_string(at), e.problem);
        return false;
      }
    }
  }

  void process_chunk(const BagRecord& record) {
    try {
      chunk_ = detail::decompress_chunk(record.header.get("compression"), record.data,
                                        record.header.u32("size"), options_.max_chunk_bytes);
    } catch (const BagDecodeError& e) {
      if (!options_.lenient) fail_record(record.offset, "chunk: " + e.problem);
      skip(file_.position() - record.offset, "byte " + std::to_string(record.offset),
           "chunk: " + e.problem);
      return;
    }
    std::vector<Event> events = collect_events(record.offset);
    std::stable_sort(events.begin(), events.end(),
                     [](const Event& a, const Event& b) { return a.time < b.time; });
    for (const Event& e : events) dispatch(e, record.offset);
  }

  std::string chunk_place(std::uint64_t chunk_at, std::uint64_t offset) const {
    return "byte " + std::to_string(chunk_at) + " (chunk), offset " + std::to_string(offset) +
           " of its data";
  }

  std::vector<Event> collect_events(std::uint64_t chunk_at) {
    std::vector<Event> events;
    detail::ByteReader reader(chunk_);
    try {
      while (reader.remaining() > 0) {
        const BagRecord r = detail::read_record(reader);
        if (r.header.op() == BagOp::kConnection) add_connection(r);
        if (r.header.op() != BagOp::kMessage) continue;
        const auto role = roles_.find(r.header.u32("conn"));
        if (role == roles_.end())
          throw BagDecodeError{r.offset, "message on an unknown connection"};
        if (role->second == Role::kNone) {
          ++stats_.records_ignored;
          continue;
        }
        events.push_back({r.header.time("time"), r.offset, role->second, r.data});
      }
    } catch (const BagDecodeError& e) {
      const std::string where = chunk_place(chunk_at, e.offset);
      if (!options_.lenient) throw InputError(name_, where, e.problem);
      skip(reader.remaining(), where, e.problem);
    }
    return events;
  }

  void dispatch(const Event& e, std::uint64_t chunk_at) {
    try {
      if (e.role == Role::kScan) sync_.add_scan(detail::decode_laser_scan(e.data));
      if (e.role == Role::kOdom) sync_.add_odometry(detail::decode_odometry(e.data));
      if (e.role == Role::kTf) sync_.add_transforms(detail::decode_tf(e.data));
      ++stats_.records_read;
    } catch (const BagDecodeError& d) {
      const std::string where =
          chunk_place(chunk_at, e.offset) + ", message offset " + std::to_string(d.offset);
      if (!options_.lenient) throw InputError(name_, where, d.problem);
      skip(e.data.size(), where, d.problem);
    }
  }

  std::string name_;
  detail::BagFile file_;
  ReaderOptions options_;
  detail::ScanSync sync_;
  ReadStats stats_;
  std::map<std::uint32_t, Role> roles_;
  std::string scan_topic_;
  std::string odom_topic_;
  std::string chunk_;
  std::deque<ScanFrame> ready_;
  std::uint64_t index_pos_ = 0;  ///< from the bag header; 0 in a bag that was never closed
  std::size_t frames_ = 0;       ///< frames returned so far
  bool finished_ = false;
};

}  // namespace

std::unique_ptr<ScanSource> open_ros_bag(const std::filesystem::path& path,
                                         const ReaderOptions& options) {
  return std::make_unique<BagSource>(path, options);
}

}  // namespace mote::logs
