// mote play of a CARMEN log: each scan frame becomes what a ROS 2 robot publishes for it. The
// frames' names are REP 105's: odom -> base_link -> laser.
#include <optional>

#include "mote/ros/messages.hpp"
#include "play_impl.hpp"

namespace mote::ros::detail {
namespace {

constexpr const char* kOdomFrame = "odom";
constexpr const char* kBaseFrame = "base_link";
constexpr const char* kLaserFrame = "laser";

}  // namespace

PlayResult play_carmen(const Participant& p, const PlayOptions& o) {
  const std::unique_ptr<logs::ScanSource> source = logs::open_scan_log(o.log, o.reader);
  const RawWriter scans(p, "/scan", "sensor_msgs/msg/LaserScan", kSensorQos);
  const RawWriter tf(p, "/tf", "tf2_msgs/msg/TFMessage", kTfQos);
  const RawWriter tf_static(p, "/tf_static", "tf2_msgs/msg/TFMessage", kTfStaticQos);
  wait_for_readers({&scans}, o.wait_for_readers, o.stop_requested);
  PlayResult result;
  Pacer pacer(o.rate);
  bool mounted = false;
  while (const std::optional<logs::ScanFrame> frame = source->next()) {
    if (o.stop_requested && o.stop_requested()) {
      result.stopped = true;
      return result;
    }
    pacer.wait_for(frame->stamp);
    const Stamp stamp = to_stamp(frame->stamp);
    if (!mounted) {  // a CARMEN laser does not move on the robot: one static transform
      const TransformStamped mount{{stamp, kBaseFrame}, kLaserFrame, frame->scan.sensor_pose};
      tf_static.write(encode_tf(std::span(&mount, 1)));
      ++result.messages["/tf_static"];
      mounted = true;
    }
    // The odometry first: the scan waits for odometry at its stamp.
    const TransformStamped odom{{stamp, kOdomFrame}, kBaseFrame, frame->odometry};
    tf.write(encode_tf(std::span(&odom, 1)));
    ++result.messages["/tf"];
    scans.write(encode_laser_scan(to_laser_scan_message(frame->scan, kLaserFrame)));
    ++result.messages["/scan"];
  }
  result.recorded_s = pacer.span();
  linger(o);
  return result;
}

}  // namespace mote::ros::detail
