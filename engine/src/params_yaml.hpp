#pragma once
// What the two readers of a parameters file share (config_yaml.cpp reads the filter's keys,
// node_params.cpp the live node's): the YAML, the map that holds the parameters, and places
// for messages. Internal: yaml-cpp stays out of the public headers.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace mote::detail {

/// The file's text; InputError "cannot open the configuration file" when it cannot be read.
[[nodiscard]] std::string read_params_text(const std::filesystem::path& yaml);

/// The document's root map; InputError naming the line for invalid YAML, an empty file or a
/// root that is not a map.
[[nodiscard]] YAML::Node parse_params_yaml(const std::string& yaml_text, const std::string& name);

/// True for a nav2 or ROS amcl params file: the root holds an `amcl:` map.
[[nodiscard]] bool is_ros_params(const YAML::Node& root);

/// The map that holds the parameters: nav2's amcl/ros__parameters, ROS 1's amcl, or the root;
/// InputError when it is not a map.
[[nodiscard]] YAML::Node parameter_map(const YAML::Node& root, const std::string& name);

/// "line N, key 'k'" for the value of key k.
[[nodiscard]] std::string place_of(const YAML::Node& value, const std::string& key);

/// A key's name; InputError when the key is a list or a map.
[[nodiscard]] std::string key_name(const YAML::Node& key, const std::string& name);

/// True for a key read_node_params reads (node_params.cpp): the filter's reader leaves it alone.
[[nodiscard]] bool is_node_param(std::string_view key);

/// A warning in the format of InputError's message (one line, control characters escaped).
[[nodiscard]] std::string warning(const std::string& name, const std::string& place,
                                  const std::string& text);

}  // namespace mote::detail
