#pragma once
/// \file
/// Pairs bag scans with odometry and the laser mounting pose. Scans wait until odometry at or
/// after their stamp has arrived, then take the pose interpolated between the two odometry
/// messages around the stamp (nearest one at the ends of the recording), and the mounting pose
/// from the latest transforms base -> ... -> scan frame.

#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bag_messages.hpp"
#include "mote/logs/scan_source.hpp"

namespace mote::logs::detail {

class ScanSync {
 public:
  /// `odom_frame` names the odometry frame when odometry comes from tf; `base_frame`, when not
  /// empty, the robot's base frame (else the child of the odometry, from the topic or tf).
  explicit ScanSync(std::string odom_frame, std::string base_frame = {})
      : odom_frame_(std::move(odom_frame)),
        base_frame_(std::move(base_frame)),
        fixed_base_(!base_frame_.empty()) {}

  /// When true, odometry comes from nav_msgs/Odometry messages and tf odom poses are ignored.
  void use_odometry_topic() {
    if (!from_topic_) odom_.clear();
    from_topic_ = true;
  }

  void add_scan(ScanMessage scan) { pending_.push_back(std::move(scan)); }
  void add_odometry(const OdometryMessage& odom);
  void add_transforms(const std::vector<TransformMessage>& transforms);

  /// Moves every scan that is ready into `out`; at the end of the input every pending scan is
  /// ready. Returns false when scans are pending at the end and there is no odometry at all.
  bool flush(std::deque<ScanFrame>& out, bool at_end);

  /// Live input (the node): a scan whose frame has no transform to the base once its wait is
  /// over is dropped instead of being paired with the laser at the base's origin, a scan still
  /// waiting for odometry `max_wait` seconds after a newer scan is dropped, and odometry older
  /// than every pending scan's needs is forgotten, so memory stays bounded when scans stop.
  void go_live(double max_wait) {
    live_ = true;
    max_wait_ = max_wait;
  }
  /// What live input dropped so far.
  struct Dropped {
    std::size_t no_transform = 0;  ///< no transform base -> scan frame within the wait
    std::size_t no_odometry = 0;   ///< no odometry at or after the scan's stamp within the wait
    std::string last_frame;        ///< the frame of the last scan dropped for no transform
  };
  [[nodiscard]] const Dropped& dropped() const noexcept { return dropped_; }
  /// The robot's base frame as known so far (given, or the child of the odometry frame).
  [[nodiscard]] const std::string& base_frame() const noexcept { return base_frame_; }
  /// Odometry (odom -> base) at `stamp`, interpolated; nullopt before any odometry arrived.
  [[nodiscard]] std::optional<Pose2> odometry_near(double stamp) const {
    if (odom_.empty()) return std::nullopt;
    return odometry_at(stamp);
  }

 private:
  struct Stamped {
    double stamp;
    Pose2 pose;
  };
  struct Link {
    std::string parent;
    Pose2 pose;
    bool mirrored = false;
  };
  /// The laser in the base frame: scan angles a become pose.theta + (mirrored ? -a : a).
  struct Mount {
    Pose2 pose;
    bool mirrored = false;
  };

  void push_odometry(double stamp, const Pose2& pose);
  void drop_stale();
  [[nodiscard]] Pose2 odometry_at(double stamp) const;
  [[nodiscard]] std::optional<Mount> mount(const std::string& frame) const;
  [[nodiscard]] bool is_base(const std::string& frame) const;

  std::string odom_frame_;
  std::string base_frame_;
  bool fixed_base_ = false;
  bool from_topic_ = false;
  std::deque<Stamped> odom_;
  std::map<std::string, Link> links_;
  std::deque<ScanMessage> pending_;
  bool live_ = false;
  double max_wait_ = 0.0;
  Dropped dropped_;
};

}  // namespace mote::logs::detail
