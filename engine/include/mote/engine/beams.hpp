#pragma once
/// \file
/// From a recorded scan to the beams a sensor model weighs: invalid readings are dropped first,
/// then the rest are decimated to at most max_beams evenly spaced beams (design.md section 3).

#include <cstddef>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"

namespace mote {

/// How to pick beams from a scan.
struct BeamSelection {
  int max_beams = 60;           ///< at most this many beams are kept
  double range_min = -1.0;      ///< m; < 0 uses the scan's range_min
  double range_max = -1.0;      ///< m; < 0 uses the scan's; else min(this, scan's)
  bool keep_max_range = false;  ///< keep "no return" readings (the beam model's z_max term)
};

/// The selected beams, structure-of-arrays. A reading at or above range_max (or +inf) is a
/// max-range reading: kept only with keep_max_range, stored with range == range_max.
struct BeamSet {
  std::vector<float> angle;  ///< rad, in the sensor frame
  std::vector<float> range;  ///< m
  Pose2 sensor_pose;         ///< sensor in the base frame
  float range_min = 0.0F;    ///< m, effective minimum used to select
  float range_max = 0.0F;    ///< m, effective maximum used to select
  std::size_t readings = 0;  ///< readings in the scan
  std::size_t valid = 0;     ///< readings that passed the validity checks (incl. max-range)

  [[nodiscard]] std::size_t size() const noexcept { return angle.size(); }
  [[nodiscard]] bool empty() const noexcept { return angle.empty(); }
};

/// Fills out (reusing its storage) with the beams of scan selected as `selection` says:
/// readings that are NaN, -inf, negative or below range_min are dropped; readings at or above
/// range_max (or +inf) are dropped unless keep_max_range; the survivors are decimated to
/// max_beams evenly spaced ones (the first survivor is always kept).
void select_beams(const LaserScan& scan, const BeamSelection& selection, BeamSet& out);

}  // namespace mote
