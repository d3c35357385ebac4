// Reads NodeParams (frames, topics, tf, start pose, pose saving) from a nav2 params file.
#include "mote/engine/node_params.hpp"

#include <cmath>
#include <functional>
#include <string_view>

#include "mote/core/error.hpp"
#include "params_yaml.hpp"

namespace mote {

namespace {

using detail::place_of;

struct NodeKey {
  std::string_view name;
  std::string_view expected;  // for error messages
  std::function<void(NodeParams&, const YAML::Node&)> set;
};

std::string nonempty(const YAML::Node& n) {
  if (!n.IsScalar() || n.Scalar().empty()) throw YAML::BadConversion(YAML::Mark::null_mark());
  return n.Scalar();
}

double finite(const YAML::Node& n) {
  const double v = n.as<double>();
  if (!std::isfinite(v)) throw YAML::BadConversion(YAML::Mark::null_mark());
  return v;
}

template <class T>
NodeKey text(std::string_view name, T NodeParams::*member) {
  return {name, "a non-empty name",
          [member](NodeParams& p, const YAML::Node& n) { p.*member = nonempty(n); }};
}

template <class T>
NodeKey flag(std::string_view name, T NodeParams::*member) {
  return {name, "true or false",
          [member](NodeParams& p, const YAML::Node& n) { p.*member = n.as<bool>(); }};
}

// nav2 names one topic; a list gives one laser per topic.
std::vector<std::string> topics(const YAML::Node& n) {
  if (!n.IsSequence()) return {nonempty(n)};
  std::vector<std::string> list;
  for (const auto& item : n) list.push_back(nonempty(item));
  if (list.empty()) throw YAML::BadConversion(YAML::Mark::null_mark());
  return list;
}

double& pose_field(InitialPoseParams& pose, std::string_view field) {
  if (field == "x") return pose.x;
  if (field == "y") return pose.y;
  if (field == "z") return pose.z;
  if (field == "yaw") return pose.yaw;
  throw YAML::BadConversion(YAML::Mark::null_mark());
}

void set_initial_pose(NodeParams& p, const YAML::Node& n) {
  if (!n.IsMap()) throw YAML::BadConversion(YAML::Mark::null_mark());
  for (const auto& entry : n)
    pose_field(p.initial_pose, entry.first.Scalar()) = finite(entry.second);
}

NodeKey pose_key(std::string_view name) {
  const std::string_view field = name.substr(name.find('.') + 1);
  return {name, "a finite number", [field](NodeParams& p, const YAML::Node& n) {
            pose_field(p.initial_pose, field) = finite(n);
          }};
}

const std::vector<NodeKey>& node_keys() {
  static const std::vector<NodeKey> table{
      text("global_frame_id", &NodeParams::global_frame_id),
      text("odom_frame_id", &NodeParams::odom_frame_id),
      text("base_frame_id", &NodeParams::base_frame_id),
      {"scan_topic", "a topic name or a list of them",
       [](NodeParams& p, const YAML::Node& n) { p.scan_topics = topics(n); }},
      text("map_topic", &NodeParams::map_topic),
      {"transform_tolerance", "a time >= 0 in seconds",
       [](NodeParams& p, const YAML::Node& n) {
         p.transform_tolerance = finite(n);
         if (p.transform_tolerance < 0.0) throw YAML::BadConversion(YAML::Mark::null_mark());
       }},
      flag("tf_broadcast", &NodeParams::tf_broadcast),
      flag("set_initial_pose", &NodeParams::set_initial_pose),
      {"initial_pose", "a map of x, y, z and yaw (finite numbers)", set_initial_pose},
      pose_key("initial_pose.x"),
      pose_key("initial_pose.y"),
      pose_key("initial_pose.z"),
      pose_key("initial_pose.yaw"),
      flag("always_reset_initial_pose", &NodeParams::always_reset_initial_pose),
      flag("first_map_only", &NodeParams::first_map_only),
      {"save_pose_rate", "a rate in Hz (<= 0: never)",
       [](NodeParams& p, const YAML::Node& n) { p.save_pose_rate = finite(n); }},
      flag("initialize_at_saved_pose", &NodeParams::initialize_at_saved_pose),
      text("saved_pose_filepath", &NodeParams::saved_pose_filepath),
  };
  return table;
}

}  // namespace

namespace detail {

bool is_node_param(std::string_view key) {
  for (const NodeKey& k : node_keys()) {
    if (k.name == key) return true;
  }
  return false;
}

}  // namespace detail

NodeParams parse_node_params(const std::string& yaml_text, const std::string& name) {
  const YAML::Node params = detail::parameter_map(detail::parse_params_yaml(yaml_text, name), name);
  NodeParams p;
  for (const auto& entry : params) {
    const std::string key = detail::key_name(entry.first, name);
    for (const NodeKey& k : node_keys()) {
      if (k.name != key) continue;
      try {
        k.set(p, entry.second);
      } catch (const YAML::Exception&) {
        throw InputError(name, place_of(entry.second, key), "expected " + std::string(k.expected));
      }
    }
  }
  return p;
}

NodeParams read_node_params(const std::filesystem::path& yaml) {
  return parse_node_params(detail::read_params_text(yaml), yaml.string());
}

}  // namespace mote
