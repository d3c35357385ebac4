#pragma once
/// \file
/// One storage file of a ROS 2 recording (an MCAP file or a rosbag2 sqlite3 database) as a
/// stream of serialized messages in time order, with the topics it holds. The scan source
/// (ros2_reader.cpp) decodes the messages; a rosbag2 folder chains several storages.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mote/logs/scan_source.hpp"

namespace mote::logs::detail {

/// A topic (MCAP: a channel with its schema).
struct Ros2Topic {
  std::string name;
  std::string type;      ///< ROS type name, e.g. "sensor_msgs/msg/LaserScan"
  std::string encoding;  ///< message encoding, "cdr" for ROS 2
  std::string place;     ///< where it is declared, for errors ("schema id 2", "topics row 4")
  std::string schema_encoding;  ///< MCAP: "ros2msg", "ros2idl", ...; empty for sqlite3
  std::string schema_text;      ///< MCAP: the schema data
};

/// One serialized message; `data` stays valid until the next call to next().
struct Ros2Message {
  std::size_t topic = 0;     ///< index into Ros2Storage::topics()
  std::int64_t time_ns = 0;  ///< receive (log) time
  std::string_view data;     ///< CDR bytes
  std::string place;         ///< where it is in the file, for errors
};

/// What a storage knows about itself without decoding messages (for `mote info`).
struct StorageSummary {
  std::string storage;      ///< "mcap" or "sqlite3"
  std::string compression;  ///< chunk compressions seen ("zstd", "lz4", "none"), or ""
  std::string index;        ///< how the file was read ("summary and chunk index", "linear scan")
};

class Ros2Storage {
 public:
  virtual ~Ros2Storage() = default;
  [[nodiscard]] virtual const std::string& name() const = 0;
  [[nodiscard]] virtual const std::vector<Ros2Topic>& topics() const = 0;
  /// The next message in time order, nullopt at the end; throws InputError (or, lenient, counts
  /// the skipped bytes in stats()).
  [[nodiscard]] virtual std::optional<Ros2Message> next() = 0;
  [[nodiscard]] virtual const ReadStats& stats() const = 0;
  [[nodiscard]] virtual StorageSummary summary() const = 0;
};

[[nodiscard]] std::unique_ptr<Ros2Storage> open_mcap_storage(const std::filesystem::path& path,
                                                             const ReaderOptions& options);
[[nodiscard]] std::unique_ptr<Ros2Storage> open_sqlite_storage(const std::filesystem::path& path,
                                                               const ReaderOptions& options);

/// rosbag2 metadata.yaml: the storage identifier and the storage files in order.
struct Rosbag2Metadata {
  std::string storage_identifier;  ///< "sqlite3" or "mcap"
  std::vector<std::string> relative_file_paths;
  std::string compression_format;  ///< "" or "zstd" (file or message compression)
  std::string compression_mode;    ///< "", "FILE" or "MESSAGE"
};

/// Parses metadata.yaml text; throws InputError naming `name` and the key.
[[nodiscard]] Rosbag2Metadata parse_rosbag2_metadata(const std::string& text,
                                                     const std::string& name);

}  // namespace mote::logs::detail
