#pragma once
/// \file
/// The node's parts and its two threads. The receive thread waits on the DDS readers, decodes,
/// feeds the transforms and scans to the scan pairing (logs' ScanSync, the same pairing
/// `mote replay` reads bags with) and hands each ready scan to the filter thread; a scan handed
/// over while one waits replaces it. A map is prepared into a new Localizer on a thread of its
/// own (the newest one waiting, one at a time: the receive thread never waits for it) and
/// swapped in between updates. The filter thread updates and publishes.

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bag_sync.hpp"
#include "dds_endpoints.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/ros/node.hpp"
#include "warning_log.hpp"

namespace mote::ros {

using Clock = std::chrono::steady_clock;

/// A scan ready for the filter and when it arrived.
struct ReadyScan {
  logs::ScanFrame frame;
  Clock::time_point arrived;  ///< its sample was taken from DDS
  Clock::time_point ready;    ///< paired with its odometry and handed to the filter
};

/// A map waiting to be prepared: how to get its grid (a message's decoding runs on the map
/// builder's thread, not the receive thread) and where it came from.
struct MapJob {
  std::function<OccupancyGrid()> grid;
  std::string source;
};

/// A Localizer prepared for a new map, with how it was initialized.
struct PreparedFilter {
  std::unique_ptr<Localizer> filter;
  std::string how;  ///< "globally", "at the initial pose", ...
  /// Not initialized yet: the filter thread starts it at the pose of the moment it swaps it in
  /// (a big map takes seconds to prepare, and the robot moves meanwhile).
  bool at_last_pose = false;
};

/// StartPose::source of a map that replaces another while the filter tracks.
inline constexpr const char* kLastPose = "the last pose";

/// A start pose from /initialpose, the params or the pose file.
struct StartPose {
  Pose2 pose;
  Eigen::Matrix3d covariance;
  std::string source;
};

struct Node::Impl {
  explicit Impl(NodeOptions opts);
  ~Impl();

  // The receive thread (node_inputs.cpp).
  void receive_loop();
  void take_inputs();
  void take_transforms(const detail::RawReader& reader);
  void take_scans(const detail::RawReader& reader);
  void take_maps();
  void take_initial_poses();
  void hand_over_ready_scans();
  void warn_about_silence();
  void queue_map(MapJob job);
  [[nodiscard]] bool map_in_preparation() const;
  [[nodiscard]] std::uint64_t counts_maps() const;

  // The map builder's thread (node_maps.cpp): prepares the newest queued map at a time.
  void build_maps();
  [[nodiscard]] std::optional<OccupancyGrid> grid_of(const MapJob& job);
  void build_filter(const OccupancyGrid& grid, const std::string& source);
  void warn_if_global_set_capped(const Localizer& prepared) const;

  // The filter thread (node_filter.cpp).
  void filter_loop();
  void swap_in(PreparedFilter prepared);
  void start_at_last_pose(Localizer& next) const;
  void start_at(const StartPose& start);
  void process(const ReadyScan& scan);
  void record_latency(const ReadyScan& scan);
  [[nodiscard]] std::optional<StartPose> start_pose_for_new_map() const;

  // Publishing, on the filter thread (node_outputs.cpp).
  void publish_transform(double stamp);
  void publish_estimate(double stamp);
  void publish_state(double stamp);
  void maybe_save_pose(double stamp);

  NodeOptions options;
  mutable detail::WarningLog warnings;  // thread-safe
  detail::Participant participant;
  std::vector<std::unique_ptr<detail::RawReader>> scan_readers;
  detail::RawReader tf_reader;
  detail::RawReader tf_static_reader;
  detail::RawReader map_reader;
  detail::RawReader initial_pose_reader;
  detail::RawWriter tf_writer;
  detail::RawWriter pose_writer;
  detail::RawWriter cloud_writer;
  detail::RawWriter state_writer;
  detail::RawWriter diagnostics_writer;
  dds_entity_t waitset = 0;
  dds_entity_t wake_receiver = 0;  // guard condition that ends the receive loop

  // Shared between the threads, under `mutex`.
  mutable std::mutex mutex;
  std::condition_variable wake_filter;
  std::optional<ReadyScan> pending_scan;
  std::optional<PreparedFilter> pending_filter;
  std::optional<StartPose> pending_start;
  std::vector<MapJob> queued_maps;  // maps not yet prepared, oldest first
  bool building_map = false;        // the map builder's thread is running
  bool global_requested = false;
  bool nomotion_requested = false;
  bool stopping = false;
  NodeCounters counts;
  std::deque<double> latencies_ms;   // arrival -> published, of the last processed scans
  std::deque<double> processing_ms;  // ready -> published

  // The receive thread's own.
  logs::detail::ScanSync sync;
  std::deque<std::pair<double, Clock::time_point>> arrivals;  // scan stamp -> arrival
  Clock::time_point started = Clock::now();
  Clock::time_point last_scan_arrival{};
  Clock::time_point last_silence_check = Clock::now();
  std::thread map_builder;

  // The filter thread's own.
  std::unique_ptr<Localizer> filter;
  std::optional<StartPose> deferred_start;          // an /initialpose that came before the map
  std::optional<LocalizationState> reported_state;  // the last state printed
  bool have_map_to_odom = false;
  Pose2 map_to_odom;
  Clock::time_point last_pose_save{};
  Clock::time_point last_diagnostics{};

  std::thread receiver;
  std::thread filter_thread;
};

}  // namespace mote::ros
