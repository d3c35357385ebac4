#include "params_yaml.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "mote/core/error.hpp"

namespace mote::detail {

std::string read_params_text(const std::filesystem::path& yaml) {
  std::ifstream in(yaml);
  if (!in || std::filesystem::is_directory(yaml)) {
    throw InputError(yaml.string(), "", "cannot open the configuration file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

YAML::Node parse_params_yaml(const std::string& yaml_text, const std::string& name) {
  try {
    YAML::Node root = YAML::Load(yaml_text);
    if (root.IsNull()) throw InputError(name, "line 1", "no parameters: the file is empty");
    if (!root.IsMap()) {
      throw InputError(name, "line " + std::to_string(root.Mark().line + 1),
                       "expected a map of parameters");
    }
    return root;
  } catch (const YAML::Exception& e) {
    throw InputError(name, "line " + std::to_string(std::max(e.mark.line, 0) + 1),
                     "invalid YAML: " + e.msg);
  }
}

bool is_ros_params(const YAML::Node& root) { return root["amcl"] && root["amcl"].IsMap(); }

namespace {

// yaml-cpp's Node has reference semantics: assigning to a copy of `root` would rewrite the
// document itself, so each case returns its own node.
YAML::Node section(const YAML::Node& root) {
  if (!is_ros_params(root)) return root;
  const YAML::Node amcl = root["amcl"];
  return amcl["ros__parameters"] ? amcl["ros__parameters"] : amcl;
}

}  // namespace

YAML::Node parameter_map(const YAML::Node& root, const std::string& name) {
  YAML::Node params = section(root);
  if (!params.IsMap()) {
    throw InputError(name, "line " + std::to_string(params.Mark().line + 1),
                     "expected a map of parameters");
  }
  return params;
}

std::string place_of(const YAML::Node& value, const std::string& key) {
  return "line " + std::to_string(value.Mark().line + 1) + ", key '" + key + "'";
}

std::string key_name(const YAML::Node& key, const std::string& name) {
  if (!key.IsScalar()) {
    throw InputError(name, "line " + std::to_string(key.Mark().line + 1),
                     "expected a parameter name, found a list or map");
  }
  return key.Scalar();
}

std::string warning(const std::string& name, const std::string& place, const std::string& text) {
  return InputError(name, place, text).what();
}

}  // namespace mote::detail
