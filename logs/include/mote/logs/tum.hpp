#pragma once
/// \file
/// TUM RGB-D trajectory files: one pose per line, `timestamp x y z qx qy qz qw`. Planar poses
/// take yaw from the quaternion and are written with z = 0 and a rotation about z only. Also the
/// lookup of a reference pose by stamp that every user of a reference trajectory shares.

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mote/core/pose.hpp"

namespace mote::logs {

/// One trajectory entry.
struct StampedPose {
  double stamp = 0.0;  ///< s
  Pose2 pose;          ///< m, rad

  friend bool operator==(const StampedPose&, const StampedPose&) = default;
};

/// Reads a TUM trajectory; `name` is used in error messages. Blank lines and `#` comments are
/// skipped. Throws InputError (name, line) on wrong field counts, bad or non-finite numbers, a
/// quaternion of zero length, or input without a single pose.
[[nodiscard]] std::vector<StampedPose> read_tum(std::istream& in, const std::string& name);

/// Reads a TUM trajectory file. Throws InputError if it cannot be opened or is malformed.
[[nodiscard]] std::vector<StampedPose> read_tum(const std::filesystem::path& path);

/// Writes poses, stamps with 9 decimals (ns) and positions with 6 (um), so stamps round-trip.
void write_tum(std::ostream& out, std::span<const StampedPose> poses);

/// Writes a TUM trajectory file. Throws mote::Error if the file cannot be written.
void write_tum(const std::filesystem::path& path, std::span<const StampedPose> poses);

/// s: the largest stamp gap at which a reference pose stands for a scan or an estimate (the
/// default of match_reference's tolerance wherever a reference is paired).
inline constexpr double kReferenceMatchTolerance = 0.05;

/// The reference pose nearest in time to `stamp` within `tolerance` s, or nullopt. `reference`
/// must be sorted by stamp (sort_by_stamp).
[[nodiscard]] std::optional<StampedPose> match_reference(std::span<const StampedPose> reference,
                                                         double stamp, double tolerance);

/// A copy of poses sorted by stamp (stable, so equal stamps keep file order).
[[nodiscard]] std::vector<StampedPose> sort_by_stamp(std::span<const StampedPose> poses);

/// Yaw (rad, wrapped) of the unit quaternion (qx, qy, qz, qw); Z-Y-X convention.
[[nodiscard]] double yaw_from_quaternion(double qx, double qy, double qz, double qw) noexcept;

}  // namespace mote::logs
