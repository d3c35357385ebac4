// The map builder's thread: each map (the file's, or the newest message on the map topic) is
// decoded and prepared into a new Localizer there, one at a time, while the filter thread keeps
// updating on the old one and the receive thread keeps taking /tf and scans.
#include <exception>
#include <optional>
#include <string>
#include <utility>

#include "node_impl.hpp"

namespace mote::ros {

bool Node::Impl::map_in_preparation() const {
  const std::lock_guard lock(mutex);
  return building_map || queued_map.has_value();
}

void Node::Impl::queue_map(MapJob job) {
  bool start_builder = false;
  {
    const std::lock_guard lock(mutex);
    queued_map = std::move(job);  // replaces a map still waiting: the newest one matters
    start_builder = !std::exchange(building_map, true);
  }
  if (!start_builder) return;  // the running builder takes it after its current map
  // A builder that found nothing left to do has cleared building_map and is returning.
  if (map_builder.joinable()) map_builder.join();
  map_builder = std::thread([this] { build_maps(); });
}

void Node::Impl::build_maps() {
  for (;;) {
    MapJob job;
    {
      const std::lock_guard lock(mutex);
      if (stopping || !queued_map) {
        building_map = false;
        return;
      }
      job = std::move(*std::exchange(queued_map, std::nullopt));
    }
    build_filter(job);
  }
}

void Node::Impl::build_filter(const MapJob& job) {
  std::optional<OccupancyGrid> grid;
  try {
    grid.emplace(job.grid());
  } catch (const std::exception& e) {
    {
      const std::lock_guard lock(mutex);
      ++counts.malformed;
    }
    warnings.warn("malformed " + job.source,
                  "map on " + job.source + " refused, keeping the one in use: " + e.what());
    return;
  }
  try {
    const std::optional<StartPose> start = start_pose_for_new_map();
    PreparedFilter p{std::make_unique<Localizer>(*grid, options.config), "", false};
    if (start && start->source == kLastPose) {
      p.at_last_pose = true;  // the filter thread starts it where the robot is when it swaps
    } else if (start) {
      p.filter->initialize(start->pose, start->covariance);
      p.how = "at " + start->source;
    } else {
      p.filter->initialize_global();
      p.how = "globally (" + std::to_string(p.filter->particles().size()) + " particles)";
      warn_if_global_set_capped(*p.filter);
    }
    warnings.notice("map from " + job.source + ": " + std::to_string(grid->width()) + " x " +
                    std::to_string(grid->height()) + " cells; filter started " +
                    (p.at_last_pose ? "at " + std::string(kLastPose) + " when swapped in" : p.how));
    {
      const std::lock_guard lock(mutex);
      pending_filter = std::move(p);
      ++counts.maps;
    }
    wake_filter.notify_all();
  } catch (const std::exception& e) {
    warnings.warn("map refused", "map from " + job.source + " refused: " + e.what());
  }
}

void Node::Impl::warn_if_global_set_capped(const Localizer& prepared) const {
  const GlobalSetSize g = prepared.global_set();
  if (!g.capped) return;
  warnings.warn("global set capped",
                "the global set is capped at max_particles: " + std::to_string(g.particles) +
                    " particles, " + std::to_string(g.per_bin) +
                    " per KLD bin of free space (asked " +
                    std::to_string(options.config.global_particles_per_bin) +
                    "): a global start may settle at a look-alike place; give a start pose "
                    "(/initialpose, set_initial_pose) or raise max_particles");
}

}  // namespace mote::ros
