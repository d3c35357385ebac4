/// \file
/// CARMEN log reader (Montemerlo, Roy, Thrun, "Perspectives on standardization in mobile robot
/// programming: the Carnegie Mellon Navigation (CARMEN) Toolkit", IROS 2003). One message per
/// line, processed in file order because logged timestamps are not always monotonic.

#include <cstddef>
#include <deque>
#include <exception>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/logs/no_return.hpp"
#include "mote/logs/scan_source.hpp"
#include "text_fields.hpp"

namespace mote::logs {
namespace {

constexpr long long kMaxBeams = 1 << 16;

/// The no-return value of FLASER/RLASER scans is inferred from the first kInferScans moving
/// scans (NoReturnEstimator), which are held back until then: one pass over the file, at most
/// kMaxHeldFrames frames in memory (a robot standing still adds frames but not counted scans).
constexpr std::size_t kInferScans = 200;
constexpr std::size_t kMaxHeldFrames = 2000;

/// Reads `count` ranges, m; CARMEN writes finite non-negative values.
void read_ranges(detail::LineFields& f, long long count, LaserScan& scan) {
  scan.ranges.resize(static_cast<std::size_t>(count));
  for (float& r : scan.ranges) {
    const double value = f.finite("range");
    if (value < 0.0) f.fail("negative range");
    r = static_cast<float>(value);
  }
}

/// hostname logger_timestamp, the end of every message: checked like the other fields.
void read_trailer(detail::LineFields& f) {
  (void)f.word("hostname");
  (void)f.finite("logger_timestamp");
}

Pose2 read_pose(detail::LineFields& f) {
  Pose2 p;
  p.x = f.finite("x");
  p.y = f.finite("y");
  p.theta = wrap_angle(f.finite("theta"));
  return p;
}

class CarmenSource final : public ScanSource {
 public:
  CarmenSource(const std::filesystem::path& path, const ReaderOptions& options)
      : in_(path), file_(path.string()), options_(options) {
    if (!in_ || std::filesystem::is_directory(path)) {
      throw InputError(file_, "", "cannot open file");
    }
    if (options_.carmen_max_range) {
      flaser_max_ = *options_.carmen_max_range;
      flaser_source_ = "given (ReaderOptions::carmen_max_range, mote's --laser-max-range)";
      window_done_ = true;
    }
  }

  std::optional<ScanFrame> next() override {
    if (!window_done_) fill_window();
    if (!window_.empty()) {
      ScanFrame frame = std::move(window_.front());
      window_.pop_front();
      return frame;
    }
    if (pending_) std::rethrow_exception(std::exchange(pending_, nullptr));
    return read_frame();
  }

  [[nodiscard]] ReadStats stats() const override { return stats_; }

  [[nodiscard]] std::string stamp_source() const override { return "ipc_timestamp"; }

  [[nodiscard]] std::string range_max_source() const override {
    if (saw_flaser_ && saw_robotlaser_) {
      return flaser_source_ + " (FLASER/RLASER; ROBOTLASER1 lines record their own)";
    }
    if (saw_flaser_) return flaser_source_;
    return "recorded in the log (ROBOTLASER1 max_range)";
  }

 private:
  /// Reads frames until kInferScans FLASER/RLASER scans are counted (or the end, an error, or
  /// kMaxHeldFrames), then settles their range_max. An error is kept and thrown after the frames
  /// read before it, so callers see the same sequence as without the read-ahead.
  void fill_window() {
    window_done_ = true;
    std::vector<std::size_t> flaser;  // indices in window_ of FLASER/RLASER frames
    try {
      while (window_.size() < kMaxHeldFrames && estimator_.scans() < kInferScans) {
        auto frame = read_frame();
        if (!frame) break;
        if (last_was_flaser_) {
          estimator_.add(frame->scan.ranges, frame->odometry);
          flaser.push_back(window_.size());
        }
        window_.push_back(std::move(*frame));
      }
    } catch (const InputError&) {
      pending_ = std::current_exception();
    }
    settle_flaser_max();
    for (const std::size_t k : flaser) window_[k].scan.range_max = *flaser_max_;
  }

  void settle_flaser_max() {
    const NoReturnRange found = estimator_.estimate();
    if (found.range_max > 0.0F) {
      flaser_max_ = found.range_max;
      flaser_source_ = found.describe();
    } else {
      flaser_max_ = kCarmenDefaultMaxRange;
      flaser_source_ = "CARMEN default (no FLASER/RLASER reading in the first frames)";
    }
  }

  std::optional<ScanFrame> read_frame() {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_no_;
      try {
        detail::LineFields fields(line, file_, line_no_);
        if (auto frame = parse(fields)) return frame;
      } catch (const InputError& e) {
        if (!options_.lenient) throw_with_cut_hint(e);
        ++stats_.records_skipped;
        stats_.bytes_skipped += line.size() + (in_.eof() ? 0 : 1);
        if (stats_.first_error.empty()) stats_.first_error = e.what();
      }
    }
    check_end();
    return std::nullopt;
  }

  /// Strict mode: a malformed last line that ends without its newline is most likely a file cut
  /// short (a copy or recording interrupted), which --lenient reads up to the cut, as the MCAP
  /// reader does for a cut file; anything else is rethrown as it is.
  [[noreturn]] void throw_with_cut_hint(const InputError& e) const {
    if (!in_.eof()) throw e;
    throw InputError(e.file(), e.place(),
                     e.problem() +
                         " (the file ends inside this line: cut short? --lenient reads "
                         "the " +
                         std::to_string(frames_) + " scans before it)");
  }

  /// One line: a frame for scan messages, nullopt for everything else.
  std::optional<ScanFrame> parse(detail::LineFields& f) {
    if (f.empty() || f.peek(0).front() == '#') return std::nullopt;
    const std::string_view type = f.word("message type");
    if (!is_message_type(type)) {
      f.fail("expected a message type such as FLASER or ODOM, found '" + std::string(type) + "'");
    }
    last_was_flaser_ = type == "FLASER" || type == "RLASER";
    if (type == "FLASER") return count(parse_flaser(f, front_offset_));
    if (type == "RLASER") return count(parse_flaser(f, rear_offset_));
    if (type == "ROBOTLASER1") return count(parse_robotlaser(f));
    if (type == "ODOM") {
      parse_odom(f);
    } else if (type == "PARAM") {
      parse_param(f);
    } else {
      ++stats_.records_ignored;
      return std::nullopt;
    }
    ++stats_.records_read;
    return std::nullopt;
  }

  ScanFrame count(ScanFrame frame) {
    ++stats_.records_read;
    ++frames_;
    return frame;
  }

  /// At the end of the input: a read error, or a log without a single scan that no skipped
  /// line explains (an empty, cut or wrong file), is an error even in lenient mode.
  void check_end() const {
    const std::string place = "line " + std::to_string(line_no_ + 1);
    if (in_.bad()) throw InputError(file_, place, "read error");
    if (frames_ == 0 && stats_.records_skipped == 0) {
      throw InputError(file_, place,
                       "end of file without a laser scan (FLASER, RLASER or ROBOTLASER1 line)");
    }
  }

  /// CARMEN message names are identifiers (FLASER, ROBOTLASER1, ...); anything else means the
  /// line is not a CARMEN message at all (binary data, another format).
  static bool is_message_type(std::string_view type) noexcept {
    const auto alpha = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
    if (!alpha(type.front())) return false;
    for (const char c : type) {
      if (!alpha(c) && !(c >= '0' && c <= '9') && c != '_') return false;
    }
    return true;
  }

  /// FLASER/RLASER n r_1..r_n x y theta odom_x odom_y odom_theta ipc_timestamp host logger_ts.
  /// No angle fields: the field of view is 180 degrees starting at -90 degrees, so 180/181 beams
  /// are 1 degree apart and 360/361 beams half a degree.
  ScanFrame parse_flaser(detail::LineFields& f, const Pose2& mount) {
    const long long n = f.integer("beam count", 2, kMaxBeams);
    f.expect_remaining(static_cast<std::size_t>(n) + 9, "FLASER/RLASER ranges and poses");
    ScanFrame frame;
    read_ranges(f, n, frame.scan);
    (void)read_pose(f);  // laser pose: equals odometry + mount in raw logs
    frame.odometry = read_pose(f);
    frame.stamp = f.finite("ipc_timestamp");
    read_trailer(f);
    const double steps = static_cast<double>(n - n % 2);
    frame.scan.angle_min = static_cast<float>(-std::numbers::pi / 2.0);
    frame.scan.angle_increment = static_cast<float>(std::numbers::pi / steps);
    frame.scan.range_max = flaser_max_.value_or(0.0F);  // settled after the first scans
    saw_flaser_ = true;
    frame.scan.sensor_pose = mount;
    frame.scan.stamp = frame.stamp;
    return frame;
  }

  /// ROBOTLASER1 type start fov resolution max_range accuracy remission_mode n r_1..r_n
  /// n_rem rem_1.. laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv fsafe ssafe
  /// turn_axis ipc_timestamp host logger_ts. The mounting pose is the laser pose relative to the
  /// robot pose (both odometry in raw logs).
  ScanFrame parse_robotlaser(detail::LineFields& f) {
    ScanFrame frame;
    (void)f.integer("laser_type", 0, 1000);
    frame.scan.angle_min = static_cast<float>(f.finite("start_angle"));
    (void)f.finite("field_of_view");
    frame.scan.angle_increment = static_cast<float>(f.finite("angular_resolution"));
    frame.scan.range_max = static_cast<float>(f.finite("max_range"));
    saw_robotlaser_ = true;
    (void)f.finite("accuracy");
    (void)f.integer("remission_mode", 0, 1000);
    const long long n = f.integer("beam count", 1, kMaxBeams);
    if (f.remaining() < static_cast<std::size_t>(n) + 1) f.fail("ROBOTLASER1: too few ranges");
    read_ranges(f, n, frame.scan);
    const long long n_rem = f.integer("remission count", 0, kMaxBeams);
    f.expect_remaining(static_cast<std::size_t>(n_rem) + 14, "ROBOTLASER1 remissions and poses");
    for (long long i = 0; i < n_rem; ++i) (void)f.finite("remission");
    const Pose2 laser = read_pose(f);
    frame.odometry = read_pose(f);
    for (const char* name : {"tv", "rv", "forward_safety", "side_safety", "turn_axis"}) {
      (void)f.finite(name);
    }
    frame.stamp = f.finite("ipc_timestamp");
    read_trailer(f);
    frame.scan.sensor_pose = between(frame.odometry, laser);
    frame.scan.stamp = frame.stamp;
    return frame;
  }

  /// ODOM x y theta tv rv accel ipc_timestamp host logger_ts: checked, then not used (scan lines
  /// carry the odometry at the scan time).
  static void parse_odom(detail::LineFields& f) {
    f.expect_remaining(9, "ODOM");
    for (const char* name : {"x", "y", "theta", "tv", "rv", "accel", "ipc_timestamp"}) {
      (void)f.finite(name);
    }
    (void)f.word("hostname");
    (void)f.finite("logger_timestamp");
  }

  /// PARAM name value ...: the laser offsets (m, ahead of the robot centre) are kept.
  void parse_param(detail::LineFields& f) {
    const std::string_view name = f.word("parameter name");
    if (name == "robot_frontlaser_offset") front_offset_ = {f.finite("offset"), 0.0, 0.0};
    if (name == "robot_rearlaser_offset") {
      rear_offset_ = {f.finite("offset"), 0.0, std::numbers::pi};
    }
  }

  std::ifstream in_;
  std::string file_;
  ReaderOptions options_;
  ReadStats stats_;
  std::size_t line_no_ = 0;
  std::size_t frames_ = 0;
  Pose2 front_offset_;
  Pose2 rear_offset_{0.0, 0.0, std::numbers::pi};

  // FLASER/RLASER range_max: given, or inferred from the first scans (fill_window).
  std::optional<float> flaser_max_;
  std::string flaser_source_;
  NoReturnEstimator estimator_;
  bool window_done_ = false;
  std::deque<ScanFrame> window_;
  std::exception_ptr pending_;
  bool last_was_flaser_ = false;
  bool saw_flaser_ = false;
  bool saw_robotlaser_ = false;
};

}  // namespace

std::unique_ptr<ScanSource> open_carmen_log(const std::filesystem::path& path,
                                            const ReaderOptions& options) {
  return std::make_unique<CarmenSource>(path, options);
}

}  // namespace mote::logs
