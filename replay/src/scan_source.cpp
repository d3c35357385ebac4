/// \file
/// Reader selection by file extension.

#include "mote/replay/scan_source.hpp"

#include "mote/core/error.hpp"

namespace mote::replay {

std::unique_ptr<ScanSource> open_scan_log(const std::filesystem::path& path,
                                          const ReaderOptions& options) {
  const std::string ext = path.extension().string();
  if (ext == ".clf" || ext == ".log") return open_carmen_log(path, options);
  if (ext == ".bag") return open_ros_bag(path, options);
  throw InputError(
      path.string(), "",
      "unknown log type '" + ext + "': expected .clf or .log (CARMEN) or .bag (ROS 1)");
}

}  // namespace mote::replay
