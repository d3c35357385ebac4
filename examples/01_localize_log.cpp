// 01: the Localizer on a recorded log. Loads a map_server map and a CARMEN log or ROS 1 bag,
// localizes globally and prints the estimate every 50 updates.
//   example_01_localize_log MAP.yaml LOG.clf|LOG.bag
#include <cstdio>
#include <exception>

#include "mote/engine/localizer.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/maps/map_loader.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s MAP.yaml LOG.clf|LOG.bag\n", argv[0]);
    return 2;
  }
  try {
    const mote::OccupancyGrid map = mote::load_map(argv[1]);
    mote::LocalizerConfig config;  // mote's defaults (mote::nav2_defaults() for nav2_amcl's)
    config.max_particles = 20000;
    mote::Localizer localizer(map, config);
    localizer.initialize_global();

    auto log = mote::logs::open_scan_log(argv[2]);
    int updates = 0;
    while (auto frame = log->next()) {
      if (!localizer.update(frame->odometry, frame->scan)) continue;
      if (++updates % 50 != 0) continue;
      // The heaviest hypothesis matched to the map, and whether the scans fit the belief.
      const mote::Pose2& pose = localizer.estimate().refined.pose;
      const mote::UpdateStats& stats = localizer.last_update();
      std::printf("t=%.1f s  x=%.2f y=%.2f theta=%.2f  %s  particles=%zu  update=%.2f ms\n",
                  frame->stamp, pose.x, pose.y, pose.theta, mote::name_of(stats.state),
                  stats.particles, stats.ms.total);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
