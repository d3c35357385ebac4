// A kidnapped-robot log spliced from a recorded one (see kidnap.hpp).
#include "mote/sim/kidnap.hpp"

#include <cmath>
#include <string>
#include <system_error>
#include <utility>

#include "mote/core/error.hpp"
#include "mote/logs/carmen_writer.hpp"

namespace mote::sim {
namespace {

struct Split {
  std::size_t first = 0;        // scans kept from the start
  std::size_t second_from = 0;  // index of the first scan kept from the end
};

Split split_of(std::size_t n, const KidnapOptions& o) {
  const auto fraction_ok = [](double f) { return f > 0.0 && f < 1.0; };
  if (!fraction_ok(o.keep_first) || !fraction_ok(o.keep_last)) {
    throw ConfigError("kidnap: keep_first and keep_last must be in (0, 1)");
  }
  if (o.keep_first + o.keep_last > 1.0) {
    throw ConfigError("kidnap: keep_first + keep_last must not exceed 1 (the parts would overlap)");
  }
  const auto count = [n](double f) {
    return static_cast<std::size_t>(std::floor(f * static_cast<double>(n)));
  };
  const Split s{count(o.keep_first), n - count(o.keep_last)};
  if (s.first == 0 || s.second_from >= n) {
    throw ConfigError("kidnap: a log of " + std::to_string(n) +
                      " scans leaves a part empty; keep more of it");
  }
  return s;
}

// odom'_k = odom_a (+) (odom_b^-1 (+) odom_k) for the frames from `from` on.
void continue_odometry(std::vector<logs::ScanFrame>& frames, std::size_t from,
                       const Pose2& odom_a) {
  const Pose2 odom_b = frames[from].odometry;
  for (std::size_t k = from; k < frames.size(); ++k) {
    frames[k].odometry = compose(odom_a, between(odom_b, frames[k].odometry));
  }
}

std::vector<logs::StampedPose> reference_of(std::span<const logs::ScanFrame> frames,
                                            std::span<const logs::StampedPose> sorted,
                                            double tolerance) {
  std::vector<logs::StampedPose> out;
  for (const logs::ScanFrame& f : frames) {
    if (auto ref = logs::match_reference(sorted, f.stamp, tolerance)) out.push_back(*ref);
  }
  return out;
}

double carried_distance(std::span<const logs::StampedPose> sorted, double before, double after,
                        double tolerance) {
  const auto a = logs::match_reference(sorted, before, tolerance);
  const auto b = logs::match_reference(sorted, after, tolerance);
  if (!a || !b) return std::nan("");
  return std::hypot(b->pose.x - a->pose.x, b->pose.y - a->pose.y);
}

}  // namespace

KidnappedLog make_kidnapped_log(std::vector<logs::ScanFrame> frames,
                                std::span<const logs::StampedPose> reference,
                                const KidnapOptions& options) {
  const Split split = split_of(frames.size(), options);
  const Pose2 odom_a = frames[split.first - 1].odometry;
  frames.erase(frames.begin() + static_cast<std::ptrdiff_t>(split.first),
               frames.begin() + static_cast<std::ptrdiff_t>(split.second_from));
  continue_odometry(frames, split.first, odom_a);

  KidnappedLog out;
  const std::vector<logs::StampedPose> sorted = logs::sort_by_stamp(reference);
  out.reference = reference_of(frames, sorted, options.match_tolerance_s);
  out.splice_index = split.first;
  out.splice_stamp = frames[split.first].stamp;
  out.carried_m = carried_distance(sorted, frames[split.first - 1].stamp, out.splice_stamp,
                                   options.match_tolerance_s);
  out.frames = std::move(frames);
  return out;
}

KidnapFiles make_kidnap_files(logs::ScanSource& source,
                              std::span<const logs::StampedPose> reference,
                              const std::filesystem::path& out_dir, const KidnapOptions& options) {
  std::vector<logs::ScanFrame> frames;
  while (auto f = source.next()) frames.push_back(std::move(*f));
  KidnapFiles files{out_dir / "kidnap.clf", out_dir / "kidnap.tum",
                    make_kidnapped_log(std::move(frames), reference, options)};
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error(out_dir.string() + ": cannot create output folder: " + ec.message());
  logs::write_carmen_log(files.log, files.spliced.frames);
  logs::write_tum(files.reference, files.spliced.reference);
  return files;
}

}  // namespace mote::sim
