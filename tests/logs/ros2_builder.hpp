#pragma once
/// \file
/// Writes small ROS 2 recordings for tests: CDR messages in either byte order, MCAP files (per
/// mcap.dev/spec: chunked or not, none/zstd/lz4 chunks, with or without summary and CRCs) and
/// rosbag2 sqlite3 databases, so every reader path runs without shipping files.

#include <lz4frame.h>
#include <sqlite3.h>
#include <zlib.h>
#include <zstd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace mote::test::ros2 {

/// Plain CDR (XCDR1) with its encapsulation header; alignment counted after the header.
class CdrWriter {
 public:
  explicit CdrWriter(bool little = true) : little_(little) {
    out_ = std::string{'\0', static_cast<char>(little ? 1 : 0), '\0', '\0'};
  }
  CdrWriter& u32(std::uint32_t v) { return put(v, 4); }
  CdrWriter& i32(std::int32_t v) { return put(static_cast<std::uint32_t>(v), 4); }
  CdrWriter& f32(float v) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    return put(bits, 4);
  }
  CdrWriter& f64(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, 8);
    return put(bits, 8);
  }
  CdrWriter& string(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    out_ += s;
    out_.push_back('\0');
    return *this;
  }
  CdrWriter& header(double stamp, const std::string& frame) {
    const auto sec = static_cast<std::int32_t>(std::floor(stamp));
    i32(sec);
    return u32(static_cast<std::uint32_t>(std::lround((stamp - sec) * 1e9))).string(frame);
  }
  CdrWriter& pose(double x, double y, double qz, double qw, double qx = 0.0) {
    for (double v : {x, y, 0.0, qx, 0.0, qz, qw}) f64(v);
    return *this;
  }
  [[nodiscard]] const std::string& bytes() const { return out_; }

 private:
  CdrWriter& put(std::uint64_t v, std::size_t size) {
    while ((out_.size() - 4) % size != 0) out_.push_back('\0');
    for (std::size_t k = 0; k < size; ++k) {
      const std::size_t shift = 8 * (little_ ? k : size - 1 - k);
      out_.push_back(static_cast<char>((v >> shift) & 0xFFU));
    }
    return *this;
  }
  bool little_;
  std::string out_;
};

inline std::string laser_scan(double stamp, const std::string& frame,
                              const std::vector<float>& ranges, bool little = true,
                              float angle_min = -1.0F, float increment = 0.5F) {
  CdrWriter w(little);
  w.header(stamp, frame);
  for (float v : {angle_min, 1.0F, increment, 0.0F, 0.1F, 0.05F, 10.0F}) w.f32(v);
  w.u32(static_cast<std::uint32_t>(ranges.size()));
  for (float r : ranges) w.f32(r);
  w.u32(0);
  return w.bytes();
}

inline std::string odometry(double stamp, double x, double y, double theta, bool little = true) {
  CdrWriter w(little);
  w.header(stamp, "odom").string("base_link");
  w.pose(x, y, std::sin(theta / 2), std::cos(theta / 2));
  for (int k = 0; k < 36 + 6 + 36; ++k) w.f64(0.0);
  return w.bytes();
}

struct Tf {
  std::string parent, child;
  double x = 0, y = 0, theta = 0;
  bool upside_down = false;  ///< roll pi
};

inline std::string tf_message(double stamp, const std::vector<Tf>& tfs, bool little = true) {
  CdrWriter w(little);
  w.u32(static_cast<std::uint32_t>(tfs.size()));
  for (const Tf& t : tfs) {
    w.header(stamp, t.parent).string(t.child);
    // q = Rz(theta) * Rx(pi) = (cos(t/2), 0, 0, sin(t/2)) * (0, 1, 0, 0) for the roll case.
    const double c = std::cos(t.theta / 2), s = std::sin(t.theta / 2);
    if (t.upside_down) {
      for (double v : {t.x, t.y, 0.0, c, s, 0.0, 0.0}) w.f64(v);
    } else {
      w.pose(t.x, t.y, s, c);
    }
  }
  return w.bytes();
}

inline void put_le(std::string& out, std::uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFFU));
}
inline void put_str(std::string& out, const std::string& s) {
  put_le(out, s.size(), 4);
  out += s;
}
inline std::string record(std::uint8_t op, const std::string& content) {
  std::string r(1, static_cast<char>(op));
  put_le(r, content.size(), 8);
  return r + content;
}
inline std::uint32_t crc(const std::string& bytes) {
  return static_cast<std::uint32_t>(
      ::crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

inline const char* kMcapMagic = "\x89MCAP0\r\n";

/// The ros2msg schema texts of the types mote decodes (top level; dependencies left out).
inline std::string schema_text(const std::string& type) {
  if (type == "sensor_msgs/msg/LaserScan") {
    return "std_msgs/Header header # stamp\nfloat32 angle_min\nfloat32 angle_max\n"
           "float32 angle_increment\nfloat32 time_increment\nfloat32 scan_time\n"
           "float32 range_min\nfloat32 range_max\nfloat32[] ranges\nfloat32[] intensities\n"
           "================================================================================\n"
           "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n";
  }
  if (type == "nav_msgs/msg/Odometry") {
    return "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance "
           "pose\ngeometry_msgs/TwistWithCovariance twist\n";
  }
  return "geometry_msgs/TransformStamped[] transforms\n";
}

/// An MCAP file in memory.
struct McapBuilder {
  struct Msg {
    std::uint16_t channel;
    std::uint64_t time;
    std::string data;
  };
  std::string compression;  ///< "", "zstd" or "lz4"
  bool chunked = true;
  bool summary = true;
  bool crcs = true;
  std::size_t messages_per_chunk = 2;
  std::map<std::uint16_t, std::pair<std::string, std::string>> channels;  ///< topic, type
  std::map<std::string, std::string> schema_override;                     ///< type -> text
  std::vector<Msg> messages;

  void channel(std::uint16_t id, const std::string& topic, const std::string& type) {
    channels[id] = {topic, type};
  }
  void message(std::uint16_t channel, double t, const std::string& data) {
    messages.push_back({channel, static_cast<std::uint64_t>(std::llround(t * 1e9)), data});
  }

  [[nodiscard]] std::string definitions() const {
    std::string out;
    for (const auto& [id, c] : channels) {
      std::string s;
      put_le(s, id, 2);
      put_str(s, c.second);
      put_str(s, "ros2msg");
      const auto o = schema_override.find(c.second);
      put_str(s, o != schema_override.end() ? o->second : schema_text(c.second));
      out += record(0x03, s);
      std::string ch;
      put_le(ch, id, 2);
      put_le(ch, id, 2);
      put_str(ch, c.first);
      put_str(ch, "cdr");
      put_le(ch, 0, 4);
      out += record(0x04, ch);
    }
    return out;
  }

  static std::string message_record(const Msg& m, std::uint32_t seq) {
    std::string c;
    put_le(c, m.channel, 2);
    put_le(c, seq, 4);
    put_le(c, m.time, 8);
    put_le(c, m.time, 8);
    return record(0x05, c + m.data);
  }

  [[nodiscard]] std::string compress(const std::string& raw) const {
    if (compression == "zstd") {
      std::string out(ZSTD_compressBound(raw.size()), '\0');
      out.resize(ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 3));
      return out;
    }
    if (compression == "lz4") {
      std::string out(LZ4F_compressFrameBound(raw.size(), nullptr), '\0');
      out.resize(LZ4F_compressFrame(out.data(), out.size(), raw.data(), raw.size(), nullptr));
      return out;
    }
    return raw;
  }

  [[nodiscard]] std::string chunk(const std::string& records, std::uint64_t start,
                                  std::uint64_t end) const {
    std::string c;
    put_le(c, start, 8);
    put_le(c, end, 8);
    put_le(c, records.size(), 8);
    put_le(c, crcs ? crc(records) : 0, 4);
    put_str(c, compression);
    const std::string body = compress(records);
    put_le(c, body.size(), 8);
    return record(0x06, c + body);
  }

  [[nodiscard]] std::string finish() const {
    std::string out = kMcapMagic;
    std::string h;
    put_str(h, "ros2");
    put_str(h, "mote test");
    out += record(0x01, h);
    std::string chunk_indexes;
    if (!chunked) out += definitions();
    std::string pending = chunked ? definitions() : "";
    std::uint64_t start = messages.empty() ? 0 : messages.front().time, end = start;
    std::size_t in_chunk = 0;
    auto flush = [&] {
      if (pending.empty()) return;
      const std::uint64_t at = out.size();
      const std::string c = chunk(pending, start, end);
      out += c;
      std::string ci;
      put_le(ci, start, 8);
      put_le(ci, end, 8);
      put_le(ci, at, 8);
      put_le(ci, c.size(), 8);
      put_le(ci, 0, 4);
      put_le(ci, 0, 8);
      put_str(ci, compression);
      put_le(ci, c.size() - 9, 8);
      put_le(ci, pending.size(), 8);
      chunk_indexes += record(0x08, ci);
      pending.clear();
      in_chunk = 0;
    };
    for (std::size_t k = 0; k < messages.size(); ++k) {
      const std::string r = message_record(messages[k], static_cast<std::uint32_t>(k));
      if (!chunked) {
        out += r;
        continue;
      }
      if (in_chunk == 0) start = messages[k].time;
      end = messages[k].time;
      pending += r;
      if (++in_chunk == messages_per_chunk) flush();
    }
    flush();
    std::string de;
    put_le(de, crcs ? crc(out) : 0, 4);
    out += record(0x0F, de);
    std::uint64_t summary_start = 0;
    if (summary) {
      summary_start = out.size();
      out += definitions() + chunk_indexes;
      std::string st;
      put_le(st, messages.size(), 8);
      put_le(st, channels.size(), 2);
      put_le(st, channels.size(), 4);
      put_le(st, 0, 4);
      put_le(st, 0, 4);
      put_le(st, chunked ? (messages.size() + messages_per_chunk - 1) / messages_per_chunk : 0, 4);
      put_le(st, messages.empty() ? 0 : messages.front().time, 8);
      put_le(st, messages.empty() ? 0 : messages.back().time, 8);
      put_le(st, 0, 4);
      out += record(0x0B, st);
    }
    std::string f;
    put_le(f, summary_start, 8);
    put_le(f, 0, 8);
    const std::string footer_head = record(0x02, f + "    ").substr(0, 9) + f;
    const std::uint32_t summary_crc =
        summary && crcs ? crc(out.substr(summary_start) + footer_head) : 0;
    out += footer_head;
    put_le(out, summary_crc, 4);
    return out + kMcapMagic;
  }
};

/// A rosbag2 sqlite3 database at `path` with the topics (topic, type) and messages (topic
/// index, time, data) given.
inline void write_db3(const std::filesystem::path& path,
                      const std::vector<std::pair<std::string, std::string>>& topics,
                      const std::vector<std::tuple<int, double, std::string>>& messages) {
  std::filesystem::remove(path);
  sqlite3* db = nullptr;
  if (sqlite3_open(path.string().c_str(), &db) != SQLITE_OK) throw std::runtime_error("sqlite");
  sqlite3_exec(db,
               "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT "
               "NULL,serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);"
               "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,"
               "timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
               nullptr, nullptr, nullptr);
  for (std::size_t k = 0; k < topics.size(); ++k) {
    const std::string sql = "INSERT INTO topics VALUES(" + std::to_string(k + 1) + ",'" +
                            topics[k].first + "','" + topics[k].second + "','cdr','')";
    sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);
  }
  sqlite3_stmt* q = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?,?,?)", -1, &q,
                     nullptr);
  for (const auto& [topic, t, data] : messages) {
    sqlite3_bind_int(q, 1, topic + 1);
    sqlite3_bind_int64(q, 2, std::llround(t * 1e9));
    sqlite3_bind_blob(q, 3, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
    sqlite3_step(q);
    sqlite3_reset(q);
  }
  sqlite3_finalize(q);
  sqlite3_close(db);
}

}  // namespace mote::test::ros2
