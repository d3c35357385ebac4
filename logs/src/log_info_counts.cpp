/// \file
/// Counting the messages of CARMEN logs (by message type), ROS 1 bags (connection records and
/// chunks, http://wiki.ros.org/Bags/Format/2.0) and ROS 2 storages (ros2_storage.hpp).

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "bag_format.hpp"
#include "bag_messages.hpp"
#include "log_info_counts.hpp"
#include "mote/core/error.hpp"
#include "ros2_messages.hpp"
#include "ros2_reader.hpp"

namespace mote::logs::detail {
namespace {

/// Accumulates counts per (topic, type), the time span and the tf edges.
struct Counter {
  std::map<std::pair<std::string, std::string>, std::size_t> per_topic;
  std::set<std::string> frames;
  double start = INFINITY;
  double end = -INFINITY;
  std::size_t messages = 0;

  void add(const std::string& topic, const std::string& type, double time) {
    ++per_topic[{topic, type}];
    ++messages;
    start = std::min(start, time);
    end = std::max(end, time);
  }
  void add_frames(const std::vector<TransformMessage>& tfs, bool is_static) {
    for (const TransformMessage& t : tfs) {
      frames.insert(t.parent + " -> " + t.child + (is_static ? " (static)" : ""));
    }
  }
  void fill(LogInfo& info) const {
    for (const auto& [key, n] : per_topic) info.topics.push_back({key.first, key.second, n});
    info.frames.assign(frames.begin(), frames.end());
    info.messages = messages;
    info.start = messages > 0 ? start : 0.0;
    info.end = messages > 0 ? end : 0.0;
  }
};

LogInfo count_carmen(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "", "cannot open file");
  Counter c;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
    if (w.empty() || w[0].starts_with("#")) continue;
    // ipc_timestamp hostname logger_timestamp end every message; PARAM lines have none.
    const double t = w.size() >= 4 ? std::strtod(w[w.size() - 3].c_str(), nullptr) : NAN;
    if (std::isfinite(t)) {
      c.add(w[0], "", t);
    } else {
      ++c.per_topic[{w[0], ""}];
      ++c.messages;
    }
  }
  LogInfo info;
  info.format = "CARMEN log";
  info.time_source = "ipc_timestamp";
  info.storage = "text";
  info.files = {path.string()};
  c.fill(info);
  return info;
}

class Ros1Counter {
 public:
  explicit Ros1Counter(const std::filesystem::path& path) : name_(path.string()), file_(name_) {}

  LogInfo run() {
    try {
      while (const std::optional<BagRecord> r = file_.next()) top_level(*r);
    } catch (const BagDecodeError& e) {
      throw InputError(name_, "byte " + std::to_string(e.offset), e.problem);
    }
    LogInfo info;
    info.format = "ROS 1 bag 2.0";
    info.time_source = "record times";
    info.storage = "rosbag 2.0";
    info.files = {name_};
    for (const std::string& c : compressions_) {
      info.compression += (info.compression.empty() ? "" : ", ") + c;
    }
    counter_.fill(info);
    return info;
  }

 private:
  void top_level(const BagRecord& r) {
    if (r.header.op() == BagOp::kConnection) connection(r);
    if (r.header.op() != BagOp::kChunk) return;
    const std::string compression(r.header.get("compression"));
    compressions_.insert(compression);
    const std::string chunk =
        decompress_chunk(compression, r.data, r.header.u32("size"), std::size_t{128} << 20U);
    ByteReader reader(chunk);
    while (reader.remaining() > 0) {
      const BagRecord inner = read_record(reader);
      if (inner.header.op() == BagOp::kConnection) connection(inner);
      if (inner.header.op() == BagOp::kMessage) message(inner, r.offset);
    }
  }

  void connection(const BagRecord& r) {
    const std::uint32_t id = r.header.u32("conn");
    topics_[id] = {std::string(r.header.get("topic")), std::string(BagHeader(r.data).get("type"))};
  }

  void message(const BagRecord& r, std::uint64_t chunk_at) {
    const auto it = topics_.find(r.header.u32("conn"));
    if (it == topics_.end()) throw BagDecodeError{chunk_at, "message on an unknown connection"};
    counter_.add(it->second.first, it->second.second, r.header.time("time"));
    if (it->second.second == "tf2_msgs/TFMessage" || it->second.second == "tf/tfMessage") {
      counter_.add_frames(decode_tf(r.data), it->second.first == "/tf_static");
    }
  }

  std::string name_;
  BagFile file_;
  Counter counter_;
  std::map<std::uint32_t, std::pair<std::string, std::string>> topics_;
  std::set<std::string> compressions_;
};

LogInfo count_ros2(const std::filesystem::path& path, const ReaderOptions& options) {
  const std::vector<std::unique_ptr<Ros2Storage>> storages = open_ros2_storages(path, options);
  Counter c;
  LogInfo info;
  info.format = std::filesystem::is_directory(path) ? "ROS 2 rosbag2 folder" : "ROS 2 recording";
  info.time_source = "record times";
  std::set<std::string> compressions;
  for (const auto& s : storages) {
    info.files.push_back(s->name());
    while (const std::optional<Ros2Message> m = s->next()) {
      const Ros2Topic& t = s->topics()[m->topic];
      c.add(t.name, t.type, static_cast<double>(m->time_ns) * 1e-9);
      if (ros2_type(t.type) != Ros2Type::kTf) continue;
      try {
        c.add_frames(decode_tf_cdr(m->data), t.name == "/tf_static");
      } catch (const BagDecodeError& e) {
        throw InputError(s->name(),
                         m->place + ", byte " + std::to_string(e.offset) + " of the message",
                         t.name + ": " + e.problem);
      }
    }
    const StorageSummary summary = s->summary();
    info.storage = summary.storage;
    info.index = summary.index;
    if (!summary.compression.empty()) compressions.insert(summary.compression);
  }
  for (const std::string& x : compressions) {
    info.compression += (info.compression.empty() ? "" : ", ") + x;
  }
  c.fill(info);
  return info;
}

}  // namespace

LogInfo count_messages(const std::filesystem::path& path, const ReaderOptions& options) {
  const std::string ext = path.extension().string();
  if (ext == ".clf" || ext == ".log") return count_carmen(path);
  if (ext == ".bag") return Ros1Counter(path).run();
  return count_ros2(path, options);  // open_scan_log (called next) rejects other files
}

}  // namespace mote::logs::detail
