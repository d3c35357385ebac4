#pragma once
/// \file
/// How well a log's scans fit the map at given poses: the margin search's score, and the one
/// `mote calibrate` compares the fitted and the starting config by without a reference.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "mote/calibrate/calibrate.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/maps/distance_field.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote::calibrate::detail {

/// A frame with the pose it was taken at.
struct PosedFrame {
  std::size_t frame = 0;
  Pose2 pose;
  bool usable = true;  ///< false: its refinement found no fit (left out, and so are its increments)
  PoseCovariance covariance;  ///< the refinement's (zero for reference poses)
};

/// Every frame of the log, in order.
[[nodiscard]] std::vector<logs::ScanFrame> read_frames(const CalibrationOptions& o);

/// m, the laser's no-return reading as the config caps it.
[[nodiscard]] double effective_range_max(const logs::ScanFrame& f, const LocalizerConfig& c);

/// m, the distance from a reading's endpoint to the nearest occupied cell, clamped at max_d
/// (the filter's laser_likelihood_max_dist), max_d off the map.
[[nodiscard]] double endpoint_distance(const OccupancyGrid& map, const DistanceField& field,
                                       const Pose2& sensor, double angle, double z, double max_d);

/// The readings the sensor fits use: every `step`-th, those the filter would drop left out.
template <class Visit>
void for_fit_beams(const LaserScan& scan, int beams_per_scan, Visit visit) {
  const std::size_t n = scan.ranges.size();
  const auto step = std::max<std::size_t>(1, n / static_cast<std::size_t>(beams_per_scan));
  for (std::size_t b = step / 2; b < n; b += step) {
    const double z = scan.ranges[b];
    if (!(z >= scan.range_min) || std::isnan(z)) continue;  // as the filter drops them
    visit(b, z);
  }
}

/// The field a run's poses are scored under: the last round's weights with the larger of its
/// two sigma_hit (the field's understates the spread a pose slightly off meets).
[[nodiscard]] FieldMixture scoring_field(const CalibrationRound& last);

/// MarginTrial's score (margin 0): the mean over the poses of the per-beam mean log-density
/// (nats) of the endpoints under `m`, z_hit N(d; 0, sigma^2) + z_rand / range_max (table 6.3).
[[nodiscard]] MarginTrial endpoint_fit(const OccupancyGrid& map, const DistanceField& field,
                                       const std::vector<logs::ScanFrame>& frames,
                                       const std::vector<PosedFrame>& posed,
                                       const CalibrationOptions& o, double range_max,
                                       const FieldMixture& m);

}  // namespace mote::calibrate::detail
