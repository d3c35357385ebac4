#pragma once
/// \file
/// A kidnapped-robot test made from a recorded log with reference poses: the first part of the
/// log, then its last part with the odometry rewritten to continue smoothly from the end of the
/// first part. The laser scans and reference poses stay as recorded, so at the splice the robot
/// is carried to another place without the odometry noticing (Thrun et al., Probabilistic
/// Robotics, section 8.3.3: augmented MCL must recover from this).

#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

#include "mote/logs/scan_source.hpp"
#include "mote/logs/tum.hpp"

namespace mote::sim {

/// Which parts of the log are kept, as fractions of its scan count.
struct KidnapOptions {
  double keep_first = 0.4;          ///< fraction of scans kept from the start, (0, 1)
  double keep_last = 0.3;           ///< fraction of scans kept from the end, (0, 1)
  double match_tolerance_s = 0.05;  ///< s, largest stamp gap between a scan and its reference
};

/// A spliced log and its reference.
struct KidnappedLog {
  std::vector<logs::ScanFrame> frames;  ///< first part, then the last part with rewritten odometry
  std::vector<logs::StampedPose> reference;  ///< the reference pose of every kept scan that has one
  std::size_t splice_index = 0;  ///< index in `frames` of the first scan after the splice
  double splice_stamp = 0.0;     ///< s, stamp of that scan (for mote replay --kidnapped-at)
  double carried_m = 0.0;  ///< m, reference distance between the scans either side of the splice
};

/// Splices `frames` (in log order): keeps floor(keep_first n) scans from the start and
/// floor(keep_last n) from the end and maps the odometry of the last part by
/// odom'_k = odom_a (+) (odom_b^-1 (+) odom_k), odom_a the last odometry of the first part and
/// odom_b the first of the last part, so the increments are unchanged and there is no jump.
/// `reference` may be in any order. Throws ConfigError when the fractions are outside (0, 1),
/// overlap (keep_first + keep_last > 1), or leave a part empty.
[[nodiscard]] KidnappedLog make_kidnapped_log(std::vector<logs::ScanFrame> frames,
                                              std::span<const logs::StampedPose> reference,
                                              const KidnapOptions& options = {});

/// The files make_kidnap_files wrote.
struct KidnapFiles {
  std::filesystem::path log;        ///< DIR/kidnap.clf (CARMEN, see carmen_writer.hpp)
  std::filesystem::path reference;  ///< DIR/kidnap.tum
  KidnappedLog spliced;             ///< what was written
};

/// Reads every frame of `source`, splices them (make_kidnapped_log) and writes out_dir/kidnap.clf
/// and out_dir/kidnap.tum, creating out_dir if needed. Throws mote::Error when a file cannot be
/// written, InputError on malformed input.
[[nodiscard]] KidnapFiles make_kidnap_files(logs::ScanSource& source,
                                            std::span<const logs::StampedPose> reference,
                                            const std::filesystem::path& out_dir,
                                            const KidnapOptions& options = {});

}  // namespace mote::sim
