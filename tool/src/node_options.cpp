#include "node_options.hpp"

#include <iostream>

#include "mote/engine/node_params.hpp"
#include "mote/ros/dds_domain.hpp"
#include "run_config.hpp"

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

// The params file's node keys (nav2_amcl's names and meanings): frames, topics, tf, the
// start pose and the saved pose.
void apply_node_params(const NodeParams& p, ros::NodeOptions& o) {
  o.global_frame = p.global_frame_id;
  o.odom_frame = p.odom_frame_id;
  o.base_frame = p.base_frame_id;
  o.scan_topics = p.scan_topics;
  o.map_topic = p.map_topic;
  o.transform_tolerance = p.transform_tolerance;
  o.tf_broadcast = p.tf_broadcast;
  if (p.set_initial_pose)
    o.initial_pose = Pose2{p.initial_pose.x, p.initial_pose.y, wrap_angle(p.initial_pose.yaw)};
  if (p.save_pose_rate > 0.0) o.save_pose_rate = p.save_pose_rate;
  if (p.initialize_at_saved_pose) o.pose_file = p.saved_pose_filepath;
  o.first_map_only = p.first_map_only;
  o.always_reset_initial_pose = p.always_reset_initial_pose;
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
  const LoadedConfig loaded = run_config(args, "node");
  o.config = loaded.config;
  if (const auto path = args.text("config")) apply_node_params(read_node_params(*path), o);
  apply_flags(args, o);
  for (const std::string& line : config_summary(loaded)) std::cout << "mote node: " << line << '\n';
  if (o.initial_pose) {
    std::cout << "mote node: start: around " << o.initial_pose->x << ", " << o.initial_pose->y
              << ", " << o.initial_pose->theta << " (m, m, rad)\n";
  }
  std::cout.flush();
  return o;
}

}  // namespace mote::tool
