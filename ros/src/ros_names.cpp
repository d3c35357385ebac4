#include "mote/ros/ros_names.hpp"

#include <cctype>

#include "mote/core/error.hpp"

namespace mote::ros {
namespace {

// ROS 2 topic names (design article "Topic and Service name mapping to DDS"): alphanumerics,
// underscores and the separating slashes; no empty token.
bool valid_topic(std::string_view name) {
  if (name.empty() || name.back() == '/' || name.find("//") != std::string_view::npos) {
    return false;
  }
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '_' && c != '/') return false;
  }
  return true;
}

}  // namespace

std::string dds_topic_name(std::string_view ros_topic) {
  if (!valid_topic(ros_topic)) {
    throw InputError("topic name", std::string(ros_topic),
                     "expected a ROS 2 topic name such as /scan (letters, digits, _ and /)");
  }
  std::string name = "rt";
  if (ros_topic.front() != '/') name += '/';
  name += ros_topic;
  return name;
}

std::string dds_type_name(std::string_view ros_type) {
  const std::size_t first = ros_type.find('/');
  const std::size_t last = ros_type.rfind('/');
  if (first == std::string_view::npos || first == last || first == 0 ||
      last + 1 == ros_type.size() || ros_type.substr(first, last - first + 1) != "/msg/") {
    throw InputError("type name", std::string(ros_type),
                     "expected a ROS 2 message type such as sensor_msgs/msg/LaserScan");
  }
  std::string name(ros_type.substr(0, first));
  name += "::msg::dds_::";
  name += ros_type.substr(last + 1);
  name += '_';
  return name;
}

}  // namespace mote::ros
