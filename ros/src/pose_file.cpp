#include "pose_file.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "mote/core/error.hpp"

namespace mote::ros {

void write_pose_file(const std::filesystem::path& path, const Pose2& pose, double stamp) {
  const std::filesystem::path temporary = path.string() + ".tmp";
  char text[256];
  const int n = std::snprintf(text, sizeof text,
                              "# mote node: the last pose while tracking (map frame)\n"
                              "x: %.6f\ny: %.6f\nyaw: %.6f\nstamp: %.6f\n",
                              pose.x, pose.y, pose.theta, stamp);
  std::FILE* f = std::fopen(temporary.c_str(), "w");
  if (f == nullptr) throw Error("cannot write the pose file " + temporary.string());
  const bool written =
      std::fwrite(text, 1, static_cast<std::size_t>(n), f) == static_cast<std::size_t>(n) &&
      std::fflush(f) == 0 && fsync(fileno(f)) == 0;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) throw Error("cannot write the pose file " + temporary.string());
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);  // atomic within one file system
  if (ec) throw Error("cannot replace " + path.string() + ": " + ec.message());
}

std::optional<Pose2> read_pose_file(const std::filesystem::path& path,
                                    detail::WarningLog& warnings) {
  std::ifstream in(path);
  if (!in) {
    warnings.notice("no saved pose in " + path.string() + " yet: starting without it");
    return std::nullopt;
  }
  double x = NAN;
  double y = NAN;
  double yaw = NAN;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string key;
    double value = NAN;
    if (!(fields >> key >> value)) continue;
    if (key == "x:") x = value;
    if (key == "y:") y = value;
    if (key == "yaw:") yaw = value;
  }
  const Pose2 pose{x, y, yaw};
  if (!is_finite(pose)) {
    warnings.warn("pose file", path.string() +
                                   ": expected finite x:, y: and yaw: lines; "
                                   "starting without the saved pose");
    return std::nullopt;
  }
  return pose;
}

}  // namespace mote::ros
