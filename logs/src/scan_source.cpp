/// \file
/// Reader selection by file extension.

#include "mote/logs/scan_source.hpp"

#include "mote/core/error.hpp"

namespace mote::logs {

std::unique_ptr<ScanSource> open_scan_log(const std::filesystem::path& path,
                                          const ReaderOptions& options) {
  const std::string ext = path.extension().string();
  if (ext == ".clf" || ext == ".log") return open_carmen_log(path, options);
  if (ext == ".bag") return open_ros_bag(path, options);
  if (ext == ".mcap" || ext == ".db3" || std::filesystem::is_directory(path)) {
    if (std::filesystem::is_directory(path) && !std::filesystem::exists(path / "metadata.yaml")) {
      throw InputError(path.string(), "", "a folder that is not a rosbag2 bag (no metadata.yaml)");
    }
    return open_ros2_bag(path, options);
  }
  throw InputError(path.string(), "",
                   "unknown log type '" + ext +
                       "': expected .clf or .log (CARMEN), .bag (ROS 1), .mcap, .db3 or a "
                       "rosbag2 folder (ROS 2)");
}

}  // namespace mote::logs
