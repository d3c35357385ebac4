// Reading the map_server YAML file (ros-planning/navigation map_server/src/main.cpp keys).
#include <yaml-cpp/yaml.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"

namespace mote {

namespace {

/// Error context for one YAML file.
struct YamlSource {
  std::string file;

  [[noreturn]] void fail(const std::string& place, const std::string& problem) const {
    throw InputError(file, place, problem);
  }
  /// "line N, key 'k'" from yaml-cpp's 0-based mark.
  static std::string where(const YAML::Node& node, const std::string& key) {
    const YAML::Mark mark = node.Mark();
    if (mark.line < 0) return "key '" + key + "'";
    return "line " + std::to_string(mark.line + 1) + ", key '" + key + "'";
  }
};

/// root[key], which must be present; scalar keys must hold a single value.
YAML::Node require(const YamlSource& src, const YAML::Node& root, const std::string& key,
                   bool scalar = true) {
  YAML::Node node = root[key];
  if (!node) src.fail("key '" + key + "'", "missing required key");
  if (scalar && !node.IsScalar()) src.fail(YamlSource::where(node, key), "expected a single value");
  return node;
}

double as_number(const YamlSource& src, const YAML::Node& node, const std::string& key) {
  double value = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, value) || !std::isfinite(value)) {
    src.fail(YamlSource::where(node, key),
             "expected a finite number, got '" + (node.IsScalar() ? node.Scalar() : "?") + "'");
  }
  return value;
}

bool as_flag(const YamlSource& src, const YAML::Node& node, const std::string& key) {
  int number = 0;
  if (YAML::convert<int>::decode(node, number) && (number == 0 || number == 1)) return number == 1;
  bool flag = false;
  if (YAML::convert<bool>::decode(node, flag)) return flag;
  src.fail(YamlSource::where(node, key), "expected 0 or 1, got '" + node.Scalar() + "'");
}

Pose2 as_origin(const YamlSource& src, const YAML::Node& node) {
  if (!node.IsSequence() || node.size() != 3) {
    src.fail(YamlSource::where(node, "origin"), "expected a list [x, y, yaw]");
  }
  return {as_number(src, node[0], "origin"), as_number(src, node[1], "origin"),
          as_number(src, node[2], "origin")};
}

MapMode as_mode(const YamlSource& src, const YAML::Node& root) {
  const YAML::Node node = root["mode"];
  if (!node) return MapMode::kTrinary;
  const std::string name = node.IsScalar() ? node.Scalar() : std::string("?");
  if (name == "trinary") return MapMode::kTrinary;
  if (name == "scale") return MapMode::kScale;
  if (name == "raw") return MapMode::kRaw;
  src.fail(YamlSource::where(node, "mode"),
           "unknown mode '" + name + "' (expected trinary, scale or raw)");
}

void check_threshold(const YamlSource& src, const YAML::Node& root, const char* key, double v) {
  if (v < 0.0 || v > 1.0) {
    src.fail(YamlSource::where(root[key], key), "threshold outside [0, 1]: " + root[key].Scalar());
  }
}

void check_ranges(const YamlSource& src, const YAML::Node& root, const MapMetadata& m) {
  if (!(m.resolution > 0.0)) {
    src.fail(YamlSource::where(root["resolution"], "resolution"),
             "resolution must be positive, got " + root["resolution"].Scalar());
  }
  check_threshold(src, root, "occupied_thresh", m.occupied_thresh);
  check_threshold(src, root, "free_thresh", m.free_thresh);
  if (m.free_thresh >= m.occupied_thresh) {
    src.fail(YamlSource::where(root["free_thresh"], "free_thresh"),
             "free_thresh must be below occupied_thresh");
  }
}

// The image format whose signature the file starts with ("PNG", "PGM"...), or "" for none.
std::string_view image_kind(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char head[8] = {};
  in.read(head, sizeof head);
  const std::string_view h(head, static_cast<std::size_t>(in.gcount()));
  if (h.starts_with("\x89PNG\r\n\x1a\n")) return "PNG";
  if (h.starts_with("\xff\xd8\xff")) return "JPEG";
  if (h.starts_with("BM")) return "BMP";
  if (h.size() >= 3 && h[0] == 'P' && h[1] >= '1' && h[1] <= '6' &&
      std::isspace(static_cast<unsigned char>(h[2])) != 0) {
    return h[1] == '3' || h[1] == '6' ? "PPM" : h[1] == '2' || h[1] == '5' ? "PGM" : "PBM";
  }
  return "";
}

// An image given where the map_server YAML file that names it belongs: says so, and names the
// YAML file beside it with the same stem when there is one.
void refuse_image(const YamlSource& src, const std::filesystem::path& file) {
  const std::string_view kind = image_kind(file);
  if (kind.empty()) return;
  std::filesystem::path beside = file;
  beside.replace_extension(".yaml");
  const std::string hint = std::filesystem::is_regular_file(beside)
                               ? "; did you mean " + beside.string() + "?"
                               : "; give the .yaml file whose 'image:' key names it";
  src.fail("byte 0", "this is a " + std::string(kind) +
                         " image, not a map: a map is a map_server YAML file (image, resolution, "
                         "origin, thresholds)" +
                         hint);
}

YAML::Node parse(const YamlSource& src, const std::filesystem::path& yaml) {
  if (!std::filesystem::is_regular_file(yaml)) src.fail("", "cannot open map YAML file");
  refuse_image(src, yaml);
  try {
    YAML::Node root = YAML::LoadFile(yaml.string());
    if (!root.IsMap()) src.fail("line 1", "expected a YAML mapping of map_server keys");
    return root;
  } catch (const YAML::Exception& e) {
    src.fail("line " + std::to_string(e.mark.line + 1), "invalid YAML: " + e.msg);
  }
}

}  // namespace

MapMetadata read_map_metadata(const std::filesystem::path& yaml) {
  const YamlSource src{yaml.string()};
  const YAML::Node root = parse(src, yaml);
  MapMetadata m;
  const std::string image = require(src, root, "image").Scalar();
  if (image.empty()) src.fail(YamlSource::where(root["image"], "image"), "empty image path");
  // A NUL would end the path early when the image is opened: another file than the one named.
  if (image.find('\0') != std::string::npos) {
    src.fail(YamlSource::where(root["image"], "image"), "image path contains a NUL byte");
  }
  m.image = std::filesystem::path(image).is_absolute() ? std::filesystem::path(image)
                                                       : yaml.parent_path() / image;
  m.resolution = as_number(src, require(src, root, "resolution"), "resolution");
  m.origin = as_origin(src, require(src, root, "origin", /*scalar=*/false));
  m.negate = as_flag(src, require(src, root, "negate"), "negate");
  m.occupied_thresh = as_number(src, require(src, root, "occupied_thresh"), "occupied_thresh");
  m.free_thresh = as_number(src, require(src, root, "free_thresh"), "free_thresh");
  m.mode = as_mode(src, root);
  check_ranges(src, root, m);
  return m;
}

}  // namespace mote
