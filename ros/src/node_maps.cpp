// The map builder's thread: each map (the file's, or the newest message on the map topic) is
// decoded and prepared into a new Localizer there, one at a time, while the filter thread keeps
// updating on the old one and the receive thread keeps taking /tf and scans.
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "node_impl.hpp"

namespace mote::ros {

namespace {

// Maps waiting at most: the newest that decodes is prepared and replaces the older ones, which a
// malformed newest one must not (a map refused would leave the node with none); a burst of
// garbage on /map keeps the newest few.
constexpr std::size_t kMaxWaitingMaps = 4;

}  // namespace

bool Node::Impl::map_in_preparation() const {
  const std::lock_guard lock(mutex);
  return building_map || !queued_maps.empty();
}

void Node::Impl::queue_map(MapJob job) {
  bool start_builder = false;
  {
    const std::lock_guard lock(mutex);
    queued_maps.push_back(std::move(job));
    if (queued_maps.size() > kMaxWaitingMaps) queued_maps.erase(queued_maps.begin());
    start_builder = !std::exchange(building_map, true);
  }
  if (!start_builder) return;  // the running builder takes it after its current map
  // A builder that found nothing left to do has cleared building_map and is returning.
  if (map_builder.joinable()) map_builder.join();
  map_builder = std::thread([this] { build_maps(); });
}

void Node::Impl::build_maps() {
  for (;;) {
    std::vector<MapJob> jobs;
    {
      const std::lock_guard lock(mutex);
      if (stopping || queued_maps.empty()) {
        building_map = false;
        return;
      }
      jobs.swap(queued_maps);
    }
    // The newest map that decodes; the older ones it replaces are never decoded.
    for (auto job = jobs.rbegin(); job != jobs.rend(); ++job) {
      if (const std::optional<OccupancyGrid> grid = grid_of(*job)) {
        build_filter(*grid, job->source);
        break;
      }
    }
  }
}

std::optional<OccupancyGrid> Node::Impl::grid_of(const MapJob& job) {
  try {
    return job.grid();
  } catch (const std::exception& e) {
    {
      const std::lock_guard lock(mutex);
      ++counts.malformed;
    }
    warnings.warn("malformed " + job.source,
                  "map on " + job.source + " refused, keeping the one in use: " + e.what());
    return std::nullopt;
  }
}

void Node::Impl::build_filter(const OccupancyGrid& grid, const std::string& source) {
  try {
    const std::optional<StartPose> start = start_pose_for_new_map();
    PreparedFilter p{std::make_unique<Localizer>(grid, options.config), "", false};
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
    warnings.notice("map from " + source + ": " + std::to_string(grid.width()) + " x " +
                    std::to_string(grid.height()) + " cells; filter started " +
                    (p.at_last_pose ? "at " + std::string(kLastPose) + " when swapped in" : p.how));
    {
      const std::lock_guard lock(mutex);
      pending_filter = std::move(p);
      ++counts.maps;
    }
    wake_filter.notify_all();
  } catch (const std::exception& e) {
    warnings.warn("map refused", "map from " + source + " refused: " + e.what());
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
