/// \file
/// Reader selection by file extension.

#include "mote/logs/scan_source.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "mote/core/error.hpp"

namespace mote::logs {
namespace {

// A folder without metadata.yaml: not a rosbag2 bag, but its .db3 or .mcap storage files can be
// read alone; the message names them.
[[noreturn]] void refuse_folder(const std::filesystem::path& folder) {
  std::vector<std::string> storage;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file(ec) && (ext == ".db3" || ext == ".mcap")) {
      storage.push_back(entry.path().filename().string());
    }
  }
  std::ranges::sort(storage);
  std::string problem = "a folder that is not a rosbag2 bag (no metadata.yaml)";
  if (!storage.empty()) {
    problem +=
        "; it holds the storage file " + storage.front() +
        (storage.size() > 1 ? " (and " + std::to_string(storage.size() - 1) + " more)" : "") +
        ", which mote reads alone: give " + (folder / storage.front()).string();
  }
  throw InputError(folder.string(), "", problem);
}

}  // namespace

std::unique_ptr<ScanSource> open_scan_log(const std::filesystem::path& path,
                                          const ReaderOptions& options) {
  const std::string ext = path.extension().string();
  if (ext == ".clf" || ext == ".log") return open_carmen_log(path, options);
  if (ext == ".bag") return open_ros_bag(path, options);
  if (ext == ".mcap" || ext == ".db3" || std::filesystem::is_directory(path)) {
    if (std::filesystem::is_directory(path) && !std::filesystem::exists(path / "metadata.yaml")) {
      refuse_folder(path);
    }
    return open_ros2_bag(path, options);
  }
  throw InputError(path.string(), "",
                   "unknown log type '" + ext +
                       "': expected .clf or .log (CARMEN), .bag (ROS 1), .mcap, .db3 or a "
                       "rosbag2 folder (ROS 2)");
}

}  // namespace mote::logs
