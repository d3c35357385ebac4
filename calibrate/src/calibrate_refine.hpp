#pragma once
/// \file
/// Self-calibration's stand-in for reference poses. The filter's estimates cannot serve as they
/// are: they lean on the odometry through the motion model being fitted (with too little noise
/// the estimate follows the odometry, the residuals shrink and the fit talks itself down). Each
/// pose is therefore re-estimated from its own scan alone: the maximum of the beam model's scan
/// log-likelihood (Thrun et al., table 6.1, its hit and random parts) over (x, y, theta), started
/// at the filter's estimate, which only has to put it in the right basin. The beam model, not
/// the likelihood field: a distance field measured between cell centres puts the wall half a
/// cell behind its surface, and the pose that best fits it is off by that much.

#include <vector>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"
#include "mote/raycast/ray_caster.hpp"

namespace mote::calibrate::detail {

/// The pose within 0.3 m / 0.15 rad of `start` whose readings z best match the ray-cast ranges
/// z*, under z_hit N(z - z*; 0, sigma^2) + (1 - z_hit) / range_max. Beams are taken every
/// `step`; readings at or beyond range_max are left out.
struct Refined {
  Pose2 pose;
  double inliers = 0;         ///< share of the readings within 3 sigma of their ray-cast range
  PoseCovariance covariance;  ///< Laplace approximation at the optimum (0 when undetermined)
};

[[nodiscard]] Refined refine_pose(const RayCaster& caster, const LaserScan& scan,
                                  const Pose2& start, double z_hit, double sigma, double range_max,
                                  std::size_t step);

}  // namespace mote::calibrate::detail
