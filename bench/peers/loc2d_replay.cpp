// loc2d_replay: iris_lama's Loc2D (https://github.com/iris-ua/iris_lama) run over a recorded log
// as its ROS node (iris_lama_ros, loc2d_ros.cpp) runs it, but fed by mote's log readers and scored
// by mote's ATE code, so bench/compare-loc2d compares the two localizers and nothing else.
//
//   loc2d_replay --map MAP.yaml --log LOG --reference REF.tum [--out TRAJ.tum]
//                [--map-cells centres|corners]
//
// Prints one JSON object: scans, updates, ATE, heading and largest error, the final error, and
// the wall time of Loc2D::update per update (mean, p50, p99, max, ms; one thread: Loc2D has none).
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lama/loc2d.h"
#include "lama/pose2d.h"
#include "mote/core/error.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/logs/tum.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/replay/metrics.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Args {
  std::filesystem::path map;
  std::filesystem::path log;
  std::filesystem::path reference;
  std::filesystem::path out;  // the estimate after every update (TUM); empty = none
  bool node_corners = false;  // --map-cells corners: cells where the ROS node puts them
};

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr,
               "loc2d_replay: %s\nusage: loc2d_replay --map MAP.yaml --log LOG --reference "
               "REF.tum [--out TRAJ.tum] [--map-cells centres|corners]\n",
               problem.c_str());
  std::exit(2);
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; i += 2) {
    const std::string_view key = argv[i];
    if (i + 1 >= argc) usage(std::string(key) + " needs a value");
    const char* value = argv[i + 1];
    if (key == "--map") {
      a.map = value;
    } else if (key == "--log") {
      a.log = value;
    } else if (key == "--reference") {
      a.reference = value;
    } else if (key == "--out") {
      a.out = value;
    } else if (key == "--map-cells") {
      if (std::string_view(value) != "centres" && std::string_view(value) != "corners") {
        usage("--map-cells is centres or corners");
      }
      a.node_corners = std::string_view(value) == "corners";
    } else {
      usage("unknown argument " + std::string(key));
    }
  }
  if (a.map.empty() || a.log.empty() || a.reference.empty()) usage("--map, --log, --reference");
  return a;
}

// The ROS node's defaults (loc2d_ros.cpp): d_thresh 0.1 m, a_thresh 0.2 rad, l2_max 0.5 m,
// patch_size 32, Gauss-Newton; the map's resolution.
lama::Loc2D::Options node_options(double resolution) {
  lama::Loc2D::Options o;
  o.trans_thresh = 0.1;
  o.rot_thresh = 0.2;
  o.l2_max = 0.5;
  o.patch_size = 32;
  o.strategy = "gn";
  o.gloc_iters = 20;
  o.resolution = resolution;
  return o;
}

// Loc2D's maps hold values at the points k * resolution of their own frame (a world point goes
// to the nearest one), whatever the map's origin. The node's InitLoc2DFromOccupancyGridMsg
// places cell (i, j) at origin + (i, j) * resolution, its lower-left corner (and ignores the
// origin's yaw), so unless the origin is a multiple of the resolution every wall lands up to a
// cell away from where the map draws it, towards the lower left by half a cell on average: a
// bias of the map's origin, not of the matcher. By default the driver runs Loc2D in the map
// frame shifted so that cell (i, j)'s centre is the point (i, j) * resolution exactly, and shifts
// the start pose and the estimates by the same offset; `--map-cells corners` does as the node.
struct MapFrame {
  double dx = 0.0;  // m, Loc2D's frame origin in the map frame
  double dy = 0.0;
  double cell_x0 = 0.0;  // m, where cell (0, 0) goes in Loc2D's frame
  double cell_y0 = 0.0;

  [[nodiscard]] lama::Pose2D to_loc2d(const mote::Pose2& p) const {
    return {p.x - dx, p.y - dy, p.theta};
  }
  [[nodiscard]] mote::Pose2 from_loc2d(const lama::Pose2D& p) const {
    return {p.x() + dx, p.y() + dy, p.rotation()};
  }
};

MapFrame map_frame(const mote::OccupancyGrid& grid, bool node_corners) {
  if (grid.origin().theta != 0.0) {
    throw mote::Error("loc2d_replay: the map's origin has a yaw, which Loc2D's ROS node ignores");
  }
  const double half = 0.5 * grid.resolution();
  if (node_corners) return {0.0, 0.0, grid.origin().x, grid.origin().y};
  return {grid.origin().x + half, grid.origin().y + half, 0.0, 0.0};
}

// Free cells marked free, occupied cells marked occupied and made obstacles of the distance
// map, unknown cells left alone, as the node does.
void load_grid(lama::Loc2D& loc, const mote::OccupancyGrid& grid, const MapFrame& frame) {
  const double res = grid.resolution();
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      const Eigen::Vector3d at(frame.cell_x0 + i * res, frame.cell_y0 + j * res, 0.0);
      const mote::CellState cell = grid.at({i, j});
      if (cell == mote::CellState::kFree) {
        loc.occupancy_map->setFree(at);
      } else if (cell == mote::CellState::kOccupied) {
        loc.occupancy_map->setOccupied(at);
        loc.distance_map->addObstacle(loc.distance_map->w2m(at));
      }
    }
  }
  loc.distance_map->update();
}

// The node's onLaserScan: every beam (beam_step 1) that is finite and strictly between
// range_min and range_max (mrange 0: the scan's own range_max, which mote's reader gives), as a
// point in the laser frame; the laser's mounting pose as the cloud's sensor origin.
lama::PointCloudXYZ::Ptr to_cloud(const mote::LaserScan& scan) {
  auto cloud = std::make_shared<lama::PointCloudXYZ>();
  cloud->sensor_origin_ = Eigen::Vector3d(scan.sensor_pose.x, scan.sensor_pose.y, 0.0);
  cloud->sensor_orientation_ =
      Eigen::Quaterniond(Eigen::AngleAxisd(scan.sensor_pose.theta, Eigen::Vector3d::UnitZ()));
  cloud->points.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double range = scan.ranges[i];
    if (!std::isfinite(range) || range >= scan.range_max || range <= scan.range_min) continue;
    const double angle = static_cast<double>(scan.angle_min) +
                         static_cast<double>(i) * static_cast<double>(scan.angle_increment);
    cloud->points.emplace_back(range * std::cos(angle), range * std::sin(angle), 0.0);
  }
  return cloud;
}

// As `mote replay --reference` starts tracking (replay_run.cpp): the reference pose nearest the
// first scan's stamp within the match tolerance, else the reference's first pose.
mote::Pose2 start_pose(const std::vector<mote::logs::StampedPose>& sorted_reference,
                       double first_stamp) {
  const auto match = mote::logs::match_reference(sorted_reference, first_stamp,
                                                 mote::logs::kReferenceMatchTolerance);
  return match ? match->pose : sorted_reference.front().pose;
}

struct Run {
  std::size_t scans = 0;
  std::vector<mote::logs::StampedPose> trajectory;  // the pose after every update, at its scan
  std::vector<double> update_ms;                    // Loc2D::update of every matching update
  double first_stamp = 0.0;
};

Run run(const Args& args, const std::vector<mote::logs::StampedPose>& sorted_reference) {
  const mote::OccupancyGrid grid = mote::load_map(args.map);
  lama::Loc2D loc;
  loc.Init(node_options(grid.resolution()));
  const MapFrame frame = map_frame(grid, args.node_corners);
  load_grid(loc, grid, frame);
  const auto source = mote::logs::open_scan_log(args.log, {});
  Run r;
  while (const std::optional<mote::logs::ScanFrame> scan = source->next()) {
    if (r.scans++ == 0) {
      r.first_stamp = scan->stamp;
      loc.setPose(frame.to_loc2d(start_pose(sorted_reference, scan->stamp)));
    }
    const lama::Pose2D odom(scan->odometry.x, scan->odometry.y, scan->odometry.theta);
    if (!loc.enoughMotion(odom)) continue;
    const bool first = r.trajectory.empty();  // Loc2D's first update only stores the odometry
    const lama::PointCloudXYZ::Ptr cloud = to_cloud(scan->scan);
    const auto start = Clock::now();
    loc.update(cloud, odom, scan->stamp);
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (!first) r.update_ms.push_back(ms);
    r.trajectory.push_back({scan->stamp, frame.from_loc2d(loc.getPose())});
  }
  return r;
}

// m: the last estimate's distance to the reference pose at its stamp (NaN without one).
double final_error(const Run& r, const std::vector<mote::logs::StampedPose>& sorted_reference) {
  if (r.trajectory.empty()) return std::nan("");
  const mote::logs::StampedPose& last = r.trajectory.back();
  const auto ref = mote::logs::match_reference(sorted_reference, last.stamp,
                                               mote::logs::kReferenceMatchTolerance);
  if (!ref) return std::nan("");
  return std::hypot(last.pose.x - ref->pose.x, last.pose.y - ref->pose.y);
}

// A JSON number, or null for NaN (no matched estimate) and infinities.
std::string number(double v, int decimals) {
  if (!std::isfinite(v)) return "null";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

void print_json(const Run& r, const mote::replay::TrajectoryErrors& e, double final_m) {
  const mote::replay::Percentiles t = mote::replay::summarize(r.update_ms);
  std::printf(
      "{\"peer\": \"iris_lama Loc2D\", \"threads\": 1, \"scans\": %zu, \"updates\": %zu, "
      "\"matched\": %zu, \"ate_rmse_m\": %s, \"heading_rmse_deg\": %s, \"max_error_m\": %s, "
      "\"final_error_m\": %s, \"update_ms\": {\"mean\": %s, \"p50\": %s, \"p99\": %s, "
      "\"max\": %s}}\n",
      r.scans, r.trajectory.size(), e.matched, number(e.ate_rmse_m, 6).c_str(),
      number(e.heading_rmse_deg, 4).c_str(), number(e.max_error_m, 4).c_str(),
      number(final_m, 4).c_str(), number(t.mean, 4).c_str(), number(t.p50, 4).c_str(),
      number(t.p99, 4).c_str(), number(t.max, 4).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = parse(argc, argv);
    const auto sorted_reference = mote::logs::sort_by_stamp(mote::logs::read_tum(args.reference));
    const Run r = run(args, sorted_reference);
    mote::replay::MetricOptions metrics;
    metrics.start_stamp = r.first_stamp;
    const mote::replay::TrajectoryErrors errors =
        mote::replay::compare_trajectories(r.trajectory, sorted_reference, metrics);
    if (!args.out.empty()) mote::logs::write_tum(args.out, r.trajectory);
    print_json(r, errors, final_error(r, sorted_reference));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "loc2d_replay: %s\n", e.what());
    return 1;
  }
}
