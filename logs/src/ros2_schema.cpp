/// \file
/// ROS 2 type names and the check of MCAP "ros2msg" schema texts against what the decoders read
/// (MCAP well-known schema encodings: ros2msg is the .msg text, dependencies after "====" lines).

#include <sstream>
#include <string>
#include <vector>

#include "ros2_messages.hpp"

namespace mote::logs::detail {
namespace {

/// The top-level fields each decoder reads, as "type name" with the type's package dropped.
std::vector<std::string> expected_fields(Ros2Type type) {
  switch (type) {
    case Ros2Type::kLaserScan:
      return {"Header header",           "float32 angle_min",      "float32 angle_max",
              "float32 angle_increment", "float32 time_increment", "float32 scan_time",
              "float32 range_min",       "float32 range_max",      "float32[] ranges",
              "float32[] intensities"};
    case Ros2Type::kOdometry:
      return {"Header header", "string child_frame_id", "PoseWithCovariance pose",
              "TwistWithCovariance twist"};
    case Ros2Type::kTf:
      return {"TransformStamped[] transforms"};
    case Ros2Type::kPose:
      return {"Header header", "PoseWithCovariance pose"};
    case Ros2Type::kOther:
      break;
  }
  return {};
}

/// "type name" of a field line, package dropped; empty for blank, comment and constant lines.
std::string field_of(std::string line) {
  line = line.substr(0, line.find('#'));
  std::istringstream words(line);
  std::string type;
  std::string name;
  if (!(words >> type >> name) || line.find('=') != std::string::npos) return "";
  if (const auto slash = type.rfind('/'); slash != std::string::npos) type.erase(0, slash + 1);
  return type + " " + name;
}

std::vector<std::string> top_level_fields(std::string_view text) {
  std::vector<std::string> fields;
  std::istringstream lines{std::string(text)};
  for (std::string line; std::getline(lines, line);) {
    if (line.starts_with("====")) break;
    if (std::string f = field_of(line); !f.empty()) fields.push_back(std::move(f));
  }
  return fields;
}

}  // namespace

Ros2Type ros2_type(std::string_view name) {
  if (name == "sensor_msgs/msg/LaserScan") return Ros2Type::kLaserScan;
  if (name == "nav_msgs/msg/Odometry") return Ros2Type::kOdometry;
  if (name == "tf2_msgs/msg/TFMessage") return Ros2Type::kTf;
  if (name == "geometry_msgs/msg/PoseWithCovarianceStamped") return Ros2Type::kPose;
  return Ros2Type::kOther;
}

std::optional<std::string> schema_mismatch(Ros2Type type, std::string_view text) {
  const std::vector<std::string> want = expected_fields(type);
  const std::vector<std::string> got = top_level_fields(text);
  for (std::size_t k = 0; k < want.size(); ++k) {
    if (k >= got.size()) return "field " + std::to_string(k + 1) + " '" + want[k] + "' is missing";
    if (got[k] != want[k]) {
      return "field " + std::to_string(k + 1) + " is '" + got[k] + "', expected '" + want[k] + "'";
    }
  }
  if (got.size() > want.size()) return "extra field '" + got[want.size()] + "'";
  return std::nullopt;
}

}  // namespace mote::logs::detail
