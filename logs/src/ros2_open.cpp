/// \file
/// Opening ROS 2 logs: a rosbag2 folder (metadata.yaml, its storage files in order), a lone
/// .mcap or a lone .db3.

#include <fstream>
#include <sstream>

#include "mote/core/error.hpp"
#include "ros2_reader.hpp"

namespace mote::logs {
namespace detail {
namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::unique_ptr<Ros2Storage> open_storage(const std::filesystem::path& file,
                                          const std::string& kind, const ReaderOptions& options) {
  if (kind == "mcap") return open_mcap_storage(file, options);
  return open_sqlite_storage(file, options);
}

}  // namespace

std::vector<std::unique_ptr<Ros2Storage>> open_ros2_storages(const std::filesystem::path& path,
                                                             const ReaderOptions& options) {
  std::vector<std::unique_ptr<Ros2Storage>> out;
  if (!std::filesystem::is_directory(path)) {
    out.push_back(open_storage(path, path.extension() == ".mcap" ? "mcap" : "sqlite3", options));
    return out;
  }
  const std::filesystem::path yaml = path / "metadata.yaml";
  const Rosbag2Metadata meta = parse_rosbag2_metadata(read_text(yaml), yaml.string());
  for (const std::string& rel : meta.relative_file_paths) {
    // Older rosbag2 versions list paths with the bag folder's name in front.
    std::filesystem::path file = path / rel;
    if (!std::filesystem::exists(file)) file = path / std::filesystem::path(rel).filename();
    if (!std::filesystem::exists(file)) {
      throw InputError(yaml.string(), "key 'relative_file_paths'",
                       "storage file '" + rel + "' is not in the bag folder");
    }
    out.push_back(open_storage(file, meta.storage_identifier, options));
  }
  return out;
}

}  // namespace detail

std::unique_ptr<ScanSource> open_ros2_bag(const std::filesystem::path& path,
                                          const ReaderOptions& options) {
  return std::make_unique<detail::Ros2Source>(path.string(),
                                              detail::open_ros2_storages(path, options), options);
}

}  // namespace mote::logs
