#pragma once
/// \file
/// The parts of mote play (play.cpp: ROS 2 recordings and the map; play_carmen.cpp: CARMEN logs).

#include <chrono>
#include <functional>
#include <memory>
#include <vector>

#include "dds_endpoints.hpp"
#include "mote/ros/play.hpp"

namespace mote::ros::detail {

using Clock = std::chrono::steady_clock;

/// Holds each message back until its recorded time, scaled by the rate, has passed since the
/// first message (no waiting at rate 0).
class Pacer {
 public:
  explicit Pacer(double rate);
  void wait_for(double stamp);
  /// s between the first and the last stamp so far.
  [[nodiscard]] double span() const noexcept { return started_ ? last_ - first_ : 0.0; }

 private:
  double rate_;
  bool started_ = false;
  double first_ = 0.0;
  double last_ = 0.0;
  Clock::time_point start_;
};

/// Waits up to `seconds` until every writer has a reader (or `stop` says so).
void wait_for_readers(const std::vector<const RawWriter*>& writers, double seconds,
                      const std::function<bool()>& stop);
/// Publishes the options' map once (transient local); nullptr when there is none. The writer
/// must live as long as late readers should get the map.
[[nodiscard]] std::unique_ptr<RawWriter> publish_map(const Participant& p, const PlayOptions& o);
/// Keeps the writers alive for o.linger seconds after the end.
void linger(const PlayOptions& o);

PlayResult play_ros2(const Participant& p, const PlayOptions& o);
PlayResult play_carmen(const Participant& p, const PlayOptions& o);

}  // namespace mote::ros::detail
