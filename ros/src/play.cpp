// mote play: the pacing, the map and a ROS 2 recording's messages as they were recorded.
#include "mote/ros/play.hpp"

#include <chrono>
#include <memory>
#include <thread>

#include "dds_endpoints.hpp"
#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/ros/messages.hpp"
#include "play_impl.hpp"
#include "ros2_reader.hpp"

namespace mote::ros {
namespace {

// Each topic with the QoS its nav2 subscribers ask for (a best-effort writer would not match a
// reliable reader of /map or /tf).
detail::TopicQos qos_for(const std::string& topic, const std::string& type) {
  if (topic == "/tf_static") return detail::kTfStaticQos;
  if (topic == "/tf") return detail::kTfQos;
  if (type == "nav_msgs/msg/OccupancyGrid") return detail::kMapQos;
  if (type == "sensor_msgs/msg/LaserScan") return detail::kSensorQos;
  return detail::kDefaultQos;
}

bool is_ros2_log(const std::filesystem::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".mcap" || ext == ".db3" || std::filesystem::exists(p / "metadata.yaml");
}

}  // namespace

namespace detail {

Pacer::Pacer(double rate) : rate_(rate) {}

void Pacer::wait_for(double stamp) {
  if (!started_) {
    first_ = stamp;
    start_ = Clock::now();
    started_ = true;
  }
  last_ = stamp;
  if (rate_ <= 0.0) return;
  const auto due = start_ + std::chrono::duration_cast<Clock::duration>(
                                std::chrono::duration<double>((stamp - first_) / rate_));
  std::this_thread::sleep_until(due);
}

void wait_for_readers(const std::vector<const RawWriter*>& writers, double seconds,
                      const std::function<bool()>& stop) {
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(seconds));
  for (const RawWriter* w : writers) {
    while (w->matched() == 0 && Clock::now() < end && !(stop && stop())) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
}

std::unique_ptr<RawWriter> publish_map(const Participant& p, const PlayOptions& o) {
  if (o.map.empty()) return nullptr;
  const OccupancyGrid grid = load_map(o.map);
  auto writer = std::make_unique<RawWriter>(p, o.map_topic, "nav_msgs/msg/OccupancyGrid", kMapQos);
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  writer->write(encode_occupancy_grid(Header{to_stamp(now), "map"}, grid));
  return writer;
}

PlayResult play_ros2(const Participant& p, const PlayOptions& o) {
  std::vector<std::unique_ptr<logs::detail::Ros2Storage>> storages =
      logs::detail::open_ros2_storages(o.log, o.reader);
  std::map<std::string, std::unique_ptr<RawWriter>> writers;
  std::vector<const RawWriter*> scan_writers;
  for (const auto& s : storages) {
    for (const auto& t : s->topics()) {
      if (writers.contains(t.name) || t.encoding != "cdr") continue;
      writers[t.name] = std::make_unique<RawWriter>(p, t.name, t.type, qos_for(t.name, t.type));
      if (t.type == "sensor_msgs/msg/LaserScan") scan_writers.push_back(writers[t.name].get());
    }
  }
  wait_for_readers(scan_writers, o.wait_for_readers, o.stop_requested);
  PlayResult result;
  Pacer pacer(o.rate);
  for (const auto& s : storages) {
    while (const std::optional<logs::detail::Ros2Message> m = s->next()) {
      if (o.stop_requested && o.stop_requested()) {
        result.stopped = true;
        return result;
      }
      const logs::detail::Ros2Topic& t = s->topics()[m->topic];
      const auto w = writers.find(t.name);
      if (w == writers.end()) continue;
      pacer.wait_for(static_cast<double>(m->time_ns) * 1e-9);
      w->second->write(m->data);
      ++result.messages[t.name];
    }
  }
  result.recorded_s = pacer.span();
  linger(o);
  return result;
}

void linger(const PlayOptions& o) {
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(o.linger));
  while (Clock::now() < end && !(o.stop_requested && o.stop_requested())) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace detail

PlayResult play(const PlayOptions& options) {
  if (!(options.rate >= 0.0))
    throw ConfigError("play: --rate must be >= 0 (0: as fast as possible)");
  const auto start = detail::Clock::now();
  const detail::Participant participant(options.domain_id);
  const std::unique_ptr<detail::RawWriter> map = detail::publish_map(participant, options);
  PlayResult result = is_ros2_log(options.log) ? detail::play_ros2(participant, options)
                                               : detail::play_carmen(participant, options);
  if (map) ++result.messages[map->topic()];
  result.wall_s = std::chrono::duration<double>(detail::Clock::now() - start).count();
  return result;
}

}  // namespace mote::ros
