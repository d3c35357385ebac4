#pragma once
/// \file
/// Scan-to-map matching on the distance field: the pose that brings a scan's endpoints closest
/// to the map's obstacles, found by Gauss-Newton with a Levenberg-Marquardt safeguard over
/// (x, y, theta) from a start pose, with a Cauchy loss so that readings of things the map does
/// not hold pull little. The residual of an endpoint is its signed distance to the surface of
/// the nearest obstacle, taken through the centres of the boundary cells
/// (signed_distance_field.hpp, shifted by half a cell: negative inside a wall, so a wall drawn
/// thick does not swallow the readings), bilinearly interpolated between cell centres, and its
/// gradient is that of the interpolant
/// (the formulation of Kohlbrecher et al., "A flexible and scalable SLAM system with full 3D
/// motion estimation", SSRR 2011, on a Euclidean distance field instead of an occupancy
/// likelihood, as iris_lama's Loc2D does). The filter runs it once per update on the belief's
/// best hypothesis: the localization state (localization_state.hpp) reads how well the scan
/// fits there.

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "mote/core/pose.hpp"
#include "mote/engine/hypothesis_hold.hpp"
#include "mote/maps/signed_distance_field.hpp"

namespace mote {

/// How the match is searched and judged.
struct ScanMatchConfig {
  /// m, the Cauchy loss's scale c: a residual r weighs 1 / (1 + (r / c)^2). The sensor model's
  /// sigma_hit, the spread the model gives a reading that hits the mapped obstacle.
  double scale = 0.2;
  int max_iterations = 20;
  /// Stop once a step moves the pose less than this (m, and rad times 1 m).
  double min_step = 1e-4;
};

/// The result of one match.
struct ScanMatch {
  Pose2 pose;  ///< the refined pose (map frame)
  /// Covariance of the refined pose (x m, y m, theta rad; map frame): the robust residual
  /// variance times the inverse Gauss-Newton Hessian (the Laplace approximation), inflated by
  /// n over the effective number of independent readings (`correlation`, or the caller's
  /// estimate of it): hundreds of neighbouring readings that see the same wall error are not
  /// hundreds of independent ones, and taken as such they made the belief's chi-square gate
  /// refuse 1-2.6 % of tracking updates instead of 0.1 %. A direction the readings do not
  /// constrain gets a variance a million times the best-constrained one's. Zero when no
  /// endpoint lies near a wall.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  std::size_t endpoints = 0;  ///< endpoints matched
  /// n over the effective number of independent readings measured at this match: (1 + rho) /
  /// (1 - rho) for the lag-1 autocorrelation rho >= 0 of the robust residuals along the scan
  /// (an AR(1) model), within [1, n]. A misaligned fit correlates its residuals too (a scan
  /// turned 20 degrees misses every wall on the same side), so one match's own value would
  /// loosen the gate just where the match is wrong: the Localizer inflates by a running
  /// estimate over the matches it trusted instead.
  double correlation = 1.0;
  /// Share of the endpoints within `scale` of a mapped obstacle's surface at the refined pose.
  double hit_share = 0.0;
  int iterations = 0;  ///< Gauss-Newton steps taken
  /// Whether the search converged: an undamped step, or a rejected one, fell below min_step,
  /// or it reached max_iterations crawling (its last accepted step under a tenth of a cell, at
  /// a kink of the interpolated field). False when it stopped at max_iterations still moving,
  /// at the damping cap or on a non-finite step (and when there was nothing to match): the pose
  /// is then where the search stood, not a minimum.
  bool converged = false;
};

/// Matches scans against one distance field (which it references: keep it alive).
class ScanMatcher {
 public:
  ScanMatcher(const SignedDistanceField& field, ScanMatchConfig config);

  /// Refines `start` for the endpoints `ends` (robot frame, m). Deterministic; single-threaded.
  /// With no endpoint, returns `start` with zero shares. `correlation` > 0 inflates the
  /// covariance by that factor (a running estimate of ScanMatch::correlation); otherwise by the
  /// factor measured at this match.
  [[nodiscard]] ScanMatch match(std::span<const Point2> ends, const Pose2& start,
                                double correlation = 0.0) const;

  /// Share of `ends`, seen from `pose`, within `scale` of an obstacle's surface (no refinement).
  [[nodiscard]] double hit_share(std::span<const Point2> ends, const Pose2& pose) const;
  /// The readings of `ends` that hit (as in hit_share) from `challenger` but not from `held`,
  /// and the other way round.
  [[nodiscard]] HitDifference hit_difference(std::span<const Point2> ends, const Pose2& challenger,
                                             const Pose2& held) const;

  [[nodiscard]] const ScanMatchConfig& config() const noexcept { return config_; }

 private:
  struct Sample {
    double distance;  // m, signed, interpolated
    double gx;        // gradient in the grid frame, m per m
    double gy;
  };
  // Distance and gradient at a grid-frame point (m).
  [[nodiscard]] Sample sample(double gx, double gy) const noexcept;
  // Robust cost and its normal equations at a grid-frame pose.
  struct Normal {
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    double cost = 0.0;
    double weighted_squares = 0.0;
    double weights = 0.0;
  };
  [[nodiscard]] Normal normal_equations(std::span<const Point2> ends, const Pose2& grid_pose,
                                        bool with_jacobian) const;
  // n over the effective number of independent readings at a grid-frame pose: (1 + rho) /
  // (1 - rho) for the lag-1 autocorrelation rho >= 0 of the robust residuals in scan order,
  // within [1, n].
  [[nodiscard]] double correlation_factor(std::span<const Point2> ends,
                                          const Pose2& grid_pose) const;

  const SignedDistanceField& field_;
  ScanMatchConfig config_;
  double inv_resolution_;
  // m, added to the field: its zero lies on the faces of the boundary cells, and an occupied
  // cell says an obstacle lies somewhere in it, at its centre on average (the likelihood
  // field's distances, Thrun 6.4, run to occupied cells' centres too). Matching to the faces
  // held every reading half a cell short of the wall: Intel's ATE 0.049 m against 0.033 m for
  // iris_lama's Loc2D, whose field runs to the centres (BENCHMARKS.md, "Against a scan matcher").
  double surface_offset_;
};

}  // namespace mote
