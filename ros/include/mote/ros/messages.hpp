#pragma once
/// \file
/// The ROS 2 messages the live node publishes (and the map it subscribes to), as plain structs of
/// mote types and their CDR bytes on the wire (plain CDR, little endian, with the 4-byte
/// encapsulation header: what rmw_cyclonedds and rmw_fastrtps exchange and a rosbag2 stores).
/// Field order and types follow the .msg definitions of Humble and Jazzy; the tests compare
/// every encoder byte for byte with Cyclone DDS serializing idlc types of the same IDL.
///
/// Encoders throw ConfigError only for what CDR cannot carry (a NUL inside a string, more than
/// 2^32 - 1 elements); the map decoder throws InputError for anything malformed.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote::ros {

/// builtin_interfaces/msg/Time: seconds and nanoseconds since the epoch.
struct Stamp {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;  ///< in [0, 1e9)
  friend bool operator==(const Stamp&, const Stamp&) = default;
};

/// The stamp of a time in seconds, rounded to the nearest nanosecond (rclcpp::Time's split:
/// nanosec is never negative, so -0.25 s is sec -1, nanosec 750000000). Non-finite times and
/// times outside int32 seconds saturate to the nearest end of the range (NaN gives 0).
[[nodiscard]] Stamp to_stamp(double seconds) noexcept;
/// The stamp in seconds.
[[nodiscard]] double to_seconds(Stamp stamp) noexcept;

/// std_msgs/msg/Header.
struct Header {
  Stamp stamp;
  std::string frame_id;
};

/// geometry_msgs/msg/PoseWithCovarianceStamped of a planar pose (z = 0, rotation about z).
struct PoseWithCovarianceStamped {
  Header header;
  Pose2 pose;
  /// Covariance of (x, y, yaw), row-major, m^2, m rad, rad^2. It fills rows and columns 0, 1
  /// and 5 (x, y, rotation about z) of the message's 6x6 matrix, the rest stays 0: amcl fills
  /// indices 0, 1, 6, 7 and 35 the same way.
  std::array<double, 9> covariance{};
};

/// geometry_msgs/msg/TransformStamped of a planar transform: `transform` is the child frame
/// in the header's frame.
struct TransformStamped {
  Header header;
  std::string child_frame_id;
  Pose2 transform;
};

/// nav2_msgs/msg/Particle.
struct Particle {
  Pose2 pose;
  double weight = 0.0;
};

/// sensor_msgs/msg/LaserScan, every field as the message carries it.
struct LaserScanMessage {
  Header header;
  float angle_min = 0.0F;        ///< rad
  float angle_max = 0.0F;        ///< rad
  float angle_increment = 0.0F;  ///< rad
  float time_increment = 0.0F;   ///< s between beams
  float scan_time = 0.0F;        ///< s between scans
  float range_min = 0.0F;        ///< m
  float range_max = 0.0F;        ///< m
  std::vector<float> ranges;     ///< m
  std::vector<float> intensities;
};

/// The message of a mote scan (its stamp, angles and ranges; angle_max from the beam count,
/// timing and intensities empty as a CARMEN log lacks them).
[[nodiscard]] LaserScanMessage to_laser_scan_message(const LaserScan& scan, std::string frame_id);

/// diagnostic_msgs/msg/KeyValue.
struct KeyValue {
  std::string key;
  std::string value;
};

/// diagnostic_msgs/msg/DiagnosticStatus (level is one of the message's constants).
struct DiagnosticStatus {
  enum Level : std::uint8_t { kOk = 0, kWarn = 1, kError = 2, kStale = 3 };
  std::uint8_t level = kOk;
  std::string name;
  std::string message;
  std::string hardware_id;
  std::vector<KeyValue> values;
};

/// diagnostic_msgs/msg/DiagnosticArray.
struct DiagnosticArray {
  Header header;
  std::vector<DiagnosticStatus> status;
};

/// geometry_msgs/msg/PoseWithCovarianceStamped.
[[nodiscard]] std::string encode_pose_with_covariance(const PoseWithCovarianceStamped& msg);
/// tf2_msgs/msg/TFMessage.
[[nodiscard]] std::string encode_tf(std::span<const TransformStamped> transforms);
/// nav2_msgs/msg/ParticleCloud.
[[nodiscard]] std::string encode_particle_cloud(const Header& header,
                                                std::span<const Particle> particles);
/// sensor_msgs/msg/LaserScan.
[[nodiscard]] std::string encode_laser_scan(const LaserScanMessage& msg);
/// diagnostic_msgs/msg/DiagnosticArray.
[[nodiscard]] std::string encode_diagnostics(const DiagnosticArray& msg);

/// nav_msgs/msg/OccupancyGrid as nav2's map_server publishes a map in trinary mode: occupied
/// 100, free 0, unknown -1, rows from the bottom; map_load_time is the header's stamp.
[[nodiscard]] std::string encode_occupancy_grid(const Header& header, const OccupancyGrid& grid);

/// The default bound on a received map's cells: 2^31, what the likelihood table accepts.
inline constexpr std::uint64_t kDefaultMaxMapCells = std::uint64_t{1} << 31U;

/// A decoded nav_msgs/msg/OccupancyGrid.
struct MapMessage {
  Header header;
  Stamp map_load_time;
  OccupancyGrid grid;
};

/// Decodes nav_msgs/msg/OccupancyGrid as nav2_amcl's convertMap reads it: 0 is free, 100
/// occupied, any other value unknown; the origin's yaw comes from its quaternion. Throws
/// InputError naming `topic`, the byte offset and what was expected for malformed CDR, a zero
/// width, height or resolution, a non-finite origin or resolution, an origin tilted out of the
/// plane (a 2D map lies in the map frame's xy plane), a data length other than width * height,
/// and a grid of more than `max_cells` cells (checked before anything is allocated; more than
/// 2^32 - 1, what OccupancyGrid indexes, are refused whatever `max_cells` says).
[[nodiscard]] MapMessage decode_occupancy_grid(std::string_view bytes, std::string_view topic,
                                               std::uint64_t max_cells = kDefaultMaxMapCells);

}  // namespace mote::ros
