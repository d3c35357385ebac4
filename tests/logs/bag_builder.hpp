#pragma once
/// \file
/// Writes small ROS 1 bags (format 2.0) for tests, and re-encodes the chunks of a real bag with
/// another compression, so every chunk kind is exercised without shipping bag files.

#include <bzlib.h>
#include <lz4frame.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace mote::test {

inline void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFFU));
}
inline void put_u64(std::string& out, std::uint64_t v) {
  put_u32(out, static_cast<std::uint32_t>(v));
  put_u32(out, static_cast<std::uint32_t>(v >> 32U));
}
inline void put_f32(std::string& out, float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, 4);
  put_u32(out, bits);
}
inline void put_f64(std::string& out, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, 8);
  put_u64(out, bits);
}
inline void put_string(std::string& out, const std::string& s) {
  put_u32(out, static_cast<std::uint32_t>(s.size()));
  out += s;
}
inline void put_time(std::string& out, std::uint32_t sec, std::uint32_t nsec) {
  put_u32(out, sec);
  put_u32(out, nsec);
}
inline std::string field(const std::string& name, const std::string& value) {
  std::string out;
  put_string(out, name + "=" + value);
  return out;
}
inline std::string u32_bytes(std::uint32_t v) {
  std::string s;
  put_u32(s, v);
  return s;
}
inline std::string record(const std::string& header, const std::string& data) {
  std::string out;
  put_string(out, header);
  put_string(out, data);
  return out;
}

/// Compresses a chunk as rosbag does: "none", "bz2" (libbz2) or "lz4" (LZ4 frame).
inline std::string compress(const std::string& raw, const std::string& kind) {
  if (kind == "none") return raw;
  if (kind == "bz2") {
    std::string out(raw.size() + raw.size() / 100 + 600, '\0');
    auto len = static_cast<unsigned int>(out.size());
    if (BZ2_bzBuffToBuffCompress(out.data(), &len, const_cast<char*>(raw.data()),
                                 static_cast<unsigned int>(raw.size()), 9, 0, 30) != BZ_OK) {
      throw std::runtime_error("bz2 compression failed");
    }
    out.resize(len);
    return out;
  }
  std::string out(LZ4F_compressFrameBound(raw.size(), nullptr), '\0');
  const std::size_t len =
      LZ4F_compressFrame(out.data(), out.size(), raw.data(), raw.size(), nullptr);
  if (LZ4F_isError(len)) throw std::runtime_error("lz4 compression failed");
  out.resize(len);
  return out;
}

/// A bag with one chunk of messages followed by an index section of connection records.
class BagBuilder {
 public:
  void connection(std::uint32_t conn, const std::string& topic, const std::string& type) {
    const std::string header =
        field("op", "\x07") + field("conn", u32_bytes(conn)) + field("topic", topic);
    const std::string data = field("topic", topic) + field("type", type) + field("md5sum", "0");
    chunk_ += record(header, data);
    index_ += record(header, data);
  }
  void message(std::uint32_t conn, std::uint32_t sec, std::uint32_t nsec, const std::string& data) {
    std::string t;
    put_time(t, sec, nsec);
    chunk_ += record(
        field("op", std::string(1, '\x02')) + field("conn", u32_bytes(conn)) + field("time", t),
        data);
  }
  [[nodiscard]] std::string finish(const std::string& compression) const {
    const std::string body = compress(chunk_, compression);
    const std::string chunk =
        record(field("op", "\x05") + field("compression", compression) +
                   field("size", u32_bytes(static_cast<std::uint32_t>(chunk_.size()))),
               body);
    std::string out = "#ROSBAG V2.0\n";
    const std::uint64_t index_pos = out.size() + bag_header(0).size() + chunk.size();
    return out + bag_header(index_pos) + chunk + index_;
  }

 private:
  static std::string bag_header(std::uint64_t index_pos) {
    std::string pos;
    put_u64(pos, index_pos);
    return record(field("op", "\x03") + field("index_pos", pos) +
                      field("conn_count", u32_bytes(0)) + field("chunk_count", u32_bytes(1)),
                  std::string(16, ' '));
  }
  std::string chunk_;
  std::string index_;
};

/// sensor_msgs/LaserScan bytes.
inline std::string scan_message(std::uint32_t sec, std::uint32_t nsec, const std::string& frame,
                                const std::vector<float>& ranges) {
  std::string m;
  put_u32(m, 0);
  put_time(m, sec, nsec);
  put_string(m, frame);
  for (float v : {-1.0F, 1.0F, 0.5F, 0.0F, 0.1F, 0.05F, 10.0F}) put_f32(m, v);
  put_u32(m, static_cast<std::uint32_t>(ranges.size()));
  for (float r : ranges) put_f32(m, r);
  put_u32(m, 0);
  return m;
}

/// Header + child + planar pose (z = 0, rotation about z) as in Odometry and TransformStamped.
inline void put_stamped_pose(std::string& m, std::uint32_t sec, std::uint32_t nsec,
                             const std::string& frame, const std::string& child, double x, double y,
                             double yaw) {
  put_u32(m, 0);
  put_time(m, sec, nsec);
  put_string(m, frame);
  put_string(m, child);
  for (double v : {x, y, 0.0, 0.0, 0.0, std::sin(yaw / 2), std::cos(yaw / 2)}) put_f64(m, v);
}

/// nav_msgs/Odometry bytes.
inline std::string odom_message(std::uint32_t sec, std::uint32_t nsec, double x, double y,
                                double yaw) {
  std::string m;
  put_stamped_pose(m, sec, nsec, "odom", "base_link", x, y, yaw);
  for (int i = 0; i < 36 + 6 + 36; ++i) put_f64(m, 0.0);
  return m;
}

/// tf2_msgs/TFMessage with one transform.
inline std::string tf_message(std::uint32_t sec, std::uint32_t nsec, const std::string& parent,
                              const std::string& child, double x, double y, double yaw) {
  std::string m;
  put_u32(m, 1);
  put_stamped_pose(m, sec, nsec, parent, child, x, y, yaw);
  return m;
}

}  // namespace mote::test
