#pragma once
/// \file
/// The last pose kept across restarts (nav2 users ask for it; neither nav2_amcl nor Beluga
/// keeps one): a small YAML file written atomically, so a crash mid-write leaves the previous
/// file whole.

#include <filesystem>
#include <optional>

#include "mote/core/pose.hpp"
#include "warning_log.hpp"

namespace mote::ros {

/// Writes `pose` (map frame, its scan's stamp in s) to `path` through a temporary file in the
/// same folder, flushed and renamed over it. Throws mote::Error when the folder is not writable.
void write_pose_file(const std::filesystem::path& path, const Pose2& pose, double stamp);

/// The pose in `path`, or nullopt (with a warning saying why) when it is missing or malformed.
[[nodiscard]] std::optional<Pose2> read_pose_file(const std::filesystem::path& path,
                                                  detail::WarningLog& warnings);

}  // namespace mote::ros
