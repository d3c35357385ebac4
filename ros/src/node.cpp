#include "mote/ros/node.hpp"

#include <algorithm>
#include <deque>
#include <iostream>
#include <tuple>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "node_impl.hpp"

namespace mote::ros {
namespace {

constexpr auto kWarningInterval = std::chrono::seconds(5);

std::function<void(const std::string&)> sink_of(const NodeOptions& o) {
  if (o.log) return o.log;
  return [](const std::string& line) { std::cerr << line << '\n'; };
}

void check_options(const NodeOptions& o) {
  if (o.scan_topics.empty()) throw ConfigError("scan_topic: at least one scan topic is needed");
  if (!(o.transform_tolerance >= 0.0) || !(o.scan_wait > 0.0) || !(o.save_pose_rate > 0.0)) {
    throw ConfigError("transform_tolerance must be >= 0 s, the scan wait and save_pose_rate > 0");
  }
  if (o.initial_pose && !is_finite(*o.initial_pose)) {
    throw ConfigError("initial_pose: x, y and yaw must be finite numbers");
  }
}

// p50 and p99 of `samples`, (0, 0) for none.
std::pair<double, double> percentiles(const std::deque<double>& samples) {
  if (samples.empty()) return {0.0, 0.0};
  std::vector<double> v(samples.begin(), samples.end());
  const auto at = [&v](double q) {
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<std::size_t>(k)];
  };
  return {at(0.5), at(0.99)};
}

}  // namespace

Node::Impl::Impl(NodeOptions opts)
    : options((check_options(opts), std::move(opts))),
      warnings(sink_of(options), kWarningInterval),
      participant(options.domain_id),
      tf_reader(participant, "/tf", "tf2_msgs/msg/TFMessage", detail::kTfQos),
      tf_static_reader(participant, "/tf_static", "tf2_msgs/msg/TFMessage", detail::kTfStaticQos),
      map_reader(participant, options.map_topic, "nav_msgs/msg/OccupancyGrid", detail::kMapQos),
      initial_pose_reader(participant, "/initialpose",
                          "geometry_msgs/msg/PoseWithCovarianceStamped", detail::kInitialPoseQos),
      tf_writer(participant, "/tf", "tf2_msgs/msg/TFMessage", detail::kTfQos),
      pose_writer(participant, "/amcl_pose", "geometry_msgs/msg/PoseWithCovarianceStamped",
                  detail::kAmclPoseQos),
      cloud_writer(participant, "/particle_cloud", "nav2_msgs/msg/ParticleCloud",
                   detail::kParticleCloudQos),
      state_writer(participant, "/localization_state", "diagnostic_msgs/msg/DiagnosticArray",
                   detail::kAmclPoseQos),
      diagnostics_writer(participant, "/diagnostics", "diagnostic_msgs/msg/DiagnosticArray",
                         detail::kDefaultQos),
      sync(options.odom_frame, options.base_frame) {
  for (const std::string& topic : options.scan_topics) {
    scan_readers.push_back(std::make_unique<detail::RawReader>(
        participant, topic, "sensor_msgs/msg/LaserScan", detail::kSensorQos));
  }
  sync.go_live(options.scan_wait);
  waitset = detail::check_dds(dds_create_waitset(participant.handle()), "creating a waitset");
  wake_receiver =
      detail::check_dds(dds_create_guardcondition(participant.handle()), "creating a guard");
  detail::check_dds(dds_waitset_attach(waitset, wake_receiver, 0), "attaching the guard");
  std::vector<dds_entity_t> readers{tf_reader.handle(), tf_static_reader.handle(),
                                    map_reader.handle(), initial_pose_reader.handle()};
  for (const auto& r : scan_readers) readers.push_back(r->handle());
  for (const dds_entity_t r : readers) {
    detail::check_dds(dds_set_status_mask(r, DDS_DATA_AVAILABLE_STATUS), "reader status mask");
    detail::check_dds(dds_waitset_attach(waitset, r, r), "attaching a reader");
  }
  if (!options.map_file.empty()) {
    // Loaded here, so that a file that does not load fails the node's start with its error.
    auto grid = std::make_shared<OccupancyGrid>(load_map(options.map_file));
    queue_map({[grid] { return std::move(*grid); }, options.map_file.string()});
  }
}

Node::Impl::~Impl() {
  if (map_builder.joinable()) map_builder.join();
}

Node::Node(NodeOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  Impl& s = *impl_;
  s.warnings.notice(
      "mote node: domain " + std::to_string(s.options.domain_id) + ", scans on " +
      s.scan_readers.front()->topic() + (s.scan_readers.size() > 1 ? " and others" : "") +
      ", map on " +
      (s.options.map_file.empty() ? s.map_reader.topic() : s.options.map_file.string()) +
      ", frames " + s.options.global_frame + " -> " + s.options.odom_frame + " -> " +
      (s.options.base_frame.empty() ? "(the child of " + s.options.odom_frame + " on /tf)"
                                    : s.options.base_frame));
  s.receiver = std::thread([&s] { s.receive_loop(); });
  s.filter_thread = std::thread([&s] { s.filter_loop(); });
}

Node::~Node() { stop(); }

void Node::stop() {
  if (!impl_) return;
  Impl& s = *impl_;
  {
    const std::lock_guard lock(s.mutex);
    s.stopping = true;
  }
  s.wake_filter.notify_all();
  dds_set_guardcondition(s.wake_receiver, true);
  if (s.receiver.joinable()) s.receiver.join();
  if (s.filter_thread.joinable()) s.filter_thread.join();
  final_counters_ = counters();
  impl_.reset();  // the participant, and every entity under it, is deleted here
}

void Node::request_global_localization() {
  if (!impl_) return;
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->global_requested = true;
  }
  impl_->wake_filter.notify_all();
}

void Node::request_nomotion_update() {
  if (!impl_) return;
  const std::lock_guard lock(impl_->mutex);
  impl_->nomotion_requested = true;
}

NodeCounters Node::counters() const {
  if (!impl_) return final_counters_;
  const std::lock_guard lock(impl_->mutex);
  NodeCounters c = impl_->counts;
  std::tie(c.latency_p50_ms, c.latency_p99_ms) = percentiles(impl_->latencies_ms);
  std::tie(c.processing_p50_ms, c.processing_p99_ms) = percentiles(impl_->processing_ms);
  return c;
}

}  // namespace mote::ros
