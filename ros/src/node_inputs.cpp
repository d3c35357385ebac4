// The receive thread: DDS samples in, decoded, paired with odometry and the laser's mounting
// (logs' ScanSync, as `mote replay` pairs a bag's scans), handed to the filter thread.
#include <cmath>
#include <exception>

#include "bag_format.hpp"
#include "mote/core/error.hpp"
#include "mote/ros/messages.hpp"
#include "node_impl.hpp"
#include "ros2_messages.hpp"

namespace mote::ros {
namespace {

// How long the node waits before it says which input is missing.
constexpr auto kSilence = std::chrono::seconds(5);
// Arrival times are kept for this many scans at most (the pairing waits for a few at most).
constexpr std::size_t kMaxArrivals = 256;

std::string what_of(const std::exception& e) { return e.what(); }

// logs' CDR decoders throw BagDecodeError (an offset and a problem): as an InputError naming
// the topic, so one handler serves every input.
template <class Decode>
auto decoded(const std::string& topic, Decode&& decode) {
  try {
    return decode();
  } catch (const logs::detail::BagDecodeError& e) {
    throw InputError(topic, "byte " + std::to_string(e.offset), e.problem);
  }
}

Eigen::Matrix3d planar_covariance(const std::array<double, 36>& c) {
  Eigen::Matrix3d m;
  m << c[0], c[1], c[5], c[6], c[7], c[11], c[30], c[31], c[35];
  return m;
}

}  // namespace

void Node::Impl::receive_loop() {
  for (;;) {
    (void)dds_waitset_wait(waitset, nullptr, 0, DDS_MSECS(200));
    {
      const std::lock_guard lock(mutex);
      if (stopping) return;
    }
    take_inputs();
  }
}

void Node::Impl::take_inputs() {
  take_transforms(tf_static_reader);
  take_transforms(tf_reader);
  for (const auto& r : scan_readers) take_scans(*r);
  take_maps();
  take_initial_poses();
  hand_over_ready_scans();
  warn_about_silence();
}

void Node::Impl::take_transforms(const detail::RawReader& reader) {
  for (const std::string& bytes : reader.take()) {
    try {
      sync.add_transforms(
          decoded(reader.topic(), [&] { return logs::detail::decode_tf_cdr(bytes); }));
    } catch (const std::exception& e) {
      {
        const std::lock_guard lock(mutex);
        ++counts.malformed;
      }
      warnings.warn("malformed " + reader.topic(),
                    "malformed sample on " + reader.topic() + ", ignored: " + what_of(e));
    }
  }
}

void Node::Impl::take_scans(const detail::RawReader& reader) {
  for (const std::string& bytes : reader.take()) {
    try {
      logs::detail::ScanMessage scan =
          decoded(reader.topic(), [&] { return logs::detail::decode_laser_scan_cdr(bytes); });
      if (!std::isfinite(scan.scan.stamp)) throw InputError(reader.topic(), "header", "no stamp");
      arrivals.emplace_back(scan.scan.stamp, Clock::now());
      if (arrivals.size() > kMaxArrivals) arrivals.pop_front();
      sync.add_scan(std::move(scan));
      last_scan_arrival = Clock::now();
      const std::lock_guard lock(mutex);
      ++counts.scans_received;
    } catch (const std::exception& e) {
      {
        const std::lock_guard lock(mutex);
        ++counts.malformed;
      }
      warnings.warn("malformed " + reader.topic(),
                    "malformed scan on " + reader.topic() + ", ignored: " + what_of(e));
    }
  }
}

void Node::Impl::take_maps() {
  std::vector<std::string> maps = map_reader.take();
  if (maps.empty()) return;
  {
    const std::lock_guard lock(mutex);
    counts.map_messages += maps.size();
  }
  if (options.first_map_only && (map_in_preparation() || counts_maps() > 0)) {
    warnings.warn("first map only", "a map on " + map_reader.topic() +
                                        " ignored: first_map_only keeps the first one");
    return;
  }
  // Only the newest map matters; it is decoded where it is prepared, off this thread.
  queue_map({[this, bytes = std::move(maps.back())] {
               return decode_occupancy_grid(bytes, map_reader.topic()).grid;
             },
             map_reader.topic()});
}

void Node::Impl::take_initial_poses() {
  for (const std::string& bytes : initial_pose_reader.take()) {
    try {
      const logs::detail::PoseMessage m =
          decoded("/initialpose", [&] { return logs::detail::decode_pose_cdr(bytes); });
      const Eigen::Matrix3d cov = planar_covariance(m.covariance);
      if (!is_finite(m.pose) || !cov.allFinite()) {
        throw InputError("/initialpose", "pose", "a finite pose and covariance");
      }
      if (!m.frame_id.empty() && m.frame_id != options.global_frame) {
        throw InputError(
            "/initialpose", "header.frame_id",
            "the global frame '" + options.global_frame + "', not '" + m.frame_id + "'");
      }
      {
        const std::lock_guard lock(mutex);
        pending_start = StartPose{m.pose, cov, "/initialpose"};
        ++counts.initial_poses;
      }
      wake_filter.notify_all();
    } catch (const std::exception& e) {
      {
        const std::lock_guard lock(mutex);
        ++counts.malformed;
      }
      warnings.warn("bad /initialpose", "initial pose refused: " + what_of(e));
    }
  }
}

void Node::Impl::hand_over_ready_scans() {
  std::deque<logs::ScanFrame> ready;
  (void)sync.flush(ready, false);
  const logs::detail::ScanSync::Dropped& d = sync.dropped();
  if (d.no_transform > counts.dropped_no_transform) {
    warnings.warn(
        "no transform",
        "no transform from " +
            (sync.base_frame().empty() ? options.odom_frame + "'s child" : sync.base_frame()) +
            " to the scan's frame '" + d.last_frame + "' on /tf or /tf_static: scan dropped");
  }
  if (d.no_odometry > counts.dropped_no_odometry) {
    warnings.warn("no odometry", "no " + options.odom_frame +
                                     " -> base transform at the "
                                     "scan's stamp on /tf in time: scan dropped");
  }
  const std::lock_guard lock(mutex);
  counts.dropped_no_transform = d.no_transform;
  counts.dropped_no_odometry = d.no_odometry;
  for (logs::ScanFrame& frame : ready) {
    Clock::time_point arrived = Clock::now();
    while (!arrivals.empty() && arrivals.front().first <= frame.stamp) {
      arrived = arrivals.front().second;
      arrivals.pop_front();
    }
    if (pending_scan) ++counts.scans_skipped;  // the newest scan wins
    pending_scan = ReadyScan{std::move(frame), arrived, Clock::now()};
  }
  if (!ready.empty()) wake_filter.notify_all();
}

// After a few seconds without what the filter needs, say which of "no scans arrive", "no
// transform for the scan's frame" and "no map yet" holds.
void Node::Impl::warn_about_silence() {
  const Clock::time_point now = Clock::now();
  if (now - last_silence_check < kSilence) return;
  last_silence_check = now;
  bool have_filter = false;
  {
    const std::lock_guard lock(mutex);
    have_filter = counts.maps > 0 || pending_filter.has_value() || building_map;
  }
  if (!have_filter) {
    warnings.warn("no map", "no map yet: nothing on " + map_reader.topic() +
                                " (publishers matched: " + std::to_string(map_reader.matched()) +
                                ")");
  }
  if (now - std::max(last_scan_arrival, started) > kSilence) {
    std::string topics;
    for (const auto& r : scan_readers) {
      topics += (topics.empty() ? "" : ", ") + r->topic() +
                " (publishers matched: " + std::to_string(r->matched()) + ")";
    }
    warnings.warn("no scans", "no scans arrive on " + topics);
  }
}

}  // namespace mote::ros
