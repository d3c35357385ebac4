#include "node_options.hpp"

#include <iostream>

#include "mote/ros/dds_domain.hpp"

namespace mote::tool {
namespace {

std::vector<std::string> split_topics(const std::string& text) {
  std::vector<std::string> topics;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    if (comma > start) topics.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return topics;
}

void apply_config_file(const ParsedArgs& args, ros::NodeOptions& o) {
  if (args.has("nav2-defaults")) {
    if (args.has("config")) {
      throw args.error("nav2-defaults",
                       "cannot be combined with --config: put 'defaults: nav2' in the file");
    }
    o.config = nav2_defaults();
  }
  const std::optional<std::string> path = args.text("config");
  if (!path) return;
  LoadedConfig loaded = load_config(*path);
  for (const std::string& w : loaded.warnings) std::cerr << "mote node: warning: " << w << '\n';
  o.config = loaded.config;
}

void apply_flags(const ParsedArgs& args, ros::NodeOptions& o) {
  if (auto t = args.text("scan-topic")) o.scan_topics = split_topics(*t);
  if (o.scan_topics.empty()) throw args.error("scan-topic", "names no topic");
  if (auto t = args.text("map-topic")) o.map_topic = *t;
  if (auto m = args.text("map")) o.map_file = *m;
  if (auto p = pose_flag(args, "initial-pose")) o.initial_pose = *p;
  if (auto f = args.text("pose-file")) o.pose_file = *f;
  if (auto r = args.real("save-pose-rate", 1e-6, 1e3)) o.save_pose_rate = *r;
  if (auto f = args.text("base-frame")) o.base_frame = *f;
  if (auto f = args.text("odom-frame")) o.odom_frame = *f;
  if (auto f = args.text("global-frame")) o.global_frame = *f;
  if (auto t = args.real("transform-tolerance", 0.0, 60.0)) o.transform_tolerance = *t;
  if (args.has("no-tf")) o.tf_broadcast = false;
  o.domain_id = static_cast<int>(args.integer("domain", 0, 232).value_or(ros::ros_domain_id()));
  if (auto n = args.integer("threads", 0, 1024)) o.config.threads = static_cast<int>(*n);
  if (auto n = args.integer("max-particles", 1, 100'000'000)) {
    o.config.max_particles = static_cast<int>(*n);
  }
  if (auto n = args.integer("particles", 1, 100'000'000)) {
    o.config.min_particles = o.config.max_particles = static_cast<int>(*n);
  }
  if (auto model = args.text("model")) {
    if (*model == "likelihood_field") {
      o.config.laser_model_type = LaserModel::kLikelihoodField;
    } else if (*model == "beam") {
      o.config.laser_model_type = LaserModel::kBeam;
    } else {
      throw args.error("model", "must be likelihood_field or beam, got '" + *model + "'");
    }
  }
}

}  // namespace

ros::NodeOptions node_options(const ParsedArgs& args) {
  ros::NodeOptions o;
  apply_config_file(args, o);
  apply_flags(args, o);
  return o;
}

}  // namespace mote::tool
