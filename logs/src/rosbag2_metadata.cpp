/// \file
/// rosbag2 metadata.yaml (rosbag2_storage/yaml.hpp, versions 1-9): the key
/// rosbag2_bagfile_information holds storage_identifier, relative_file_paths (storage files in
/// order), compression_format and compression_mode.

#include <yaml-cpp/yaml.h>

#include "mote/core/error.hpp"
#include "ros2_storage.hpp"

namespace mote::logs::detail {
namespace {

std::string scalar(const YAML::Node& info, const char* key, const std::string& name) {
  const YAML::Node n = info[key];
  if (!n) return "";
  if (!n.IsScalar()) throw InputError(name, std::string("key '") + key + "'", "expected a string");
  return n.Scalar();
}

}  // namespace

Rosbag2Metadata parse_rosbag2_metadata(const std::string& text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(name, "line " + std::to_string(e.mark.line + 1), "not YAML: " + e.msg);
  }
  const YAML::Node info = root.IsMap() ? root["rosbag2_bagfile_information"] : YAML::Node();
  if (!info || !info.IsMap()) {
    throw InputError(name, "key 'rosbag2_bagfile_information'", "expected a map");
  }
  Rosbag2Metadata m;
  m.storage_identifier = scalar(info, "storage_identifier", name);
  m.compression_format = scalar(info, "compression_format", name);
  m.compression_mode = scalar(info, "compression_mode", name);
  const YAML::Node files = info["relative_file_paths"];
  if (!files || !files.IsSequence() || files.size() == 0) {
    throw InputError(name, "key 'relative_file_paths'", "expected a list of storage files");
  }
  for (const YAML::Node& f : files) {
    if (!f.IsScalar() || f.Scalar().empty()) {
      throw InputError(name, "key 'relative_file_paths'", "expected file names");
    }
    m.relative_file_paths.push_back(f.Scalar());
  }
  if (m.storage_identifier != "sqlite3" && m.storage_identifier != "mcap") {
    throw InputError(name, "key 'storage_identifier'",
                     "expected sqlite3 or mcap, got '" + m.storage_identifier + "'");
  }
  if (!m.compression_mode.empty() && m.compression_mode != "NONE") {
    throw InputError(name, "key 'compression_mode'",
                     "compressed rosbag2 bags (" + m.compression_mode + " " + m.compression_format +
                         ") are not supported: decompress them with "
                         "`ros2 bag decompress` first");
  }
  return m;
}

}  // namespace mote::logs::detail
