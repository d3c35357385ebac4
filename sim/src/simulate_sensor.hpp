#pragma once
/// \file
/// The simulator's sensors: a noisy laser scan ray cast from the true pose, and noisy odometry
/// increments. Every random number comes from the engine's counter-based Philox stream keyed by
/// (seed, scan index, purpose), so a run is reproducible and independent of evaluation order.

#include <cstdint>

#include "mote/core/pose.hpp"
#include "mote/core/scan.hpp"
#include "mote/engine/philox.hpp"
#include "mote/raycast/ray_caster.hpp"
#include "mote/sim/simulate.hpp"

namespace mote::sim::detail {

/// Stream purposes of the simulator (after the engine's own).
inline constexpr RngPurpose kSimOdometry = static_cast<RngPurpose>(65);
inline constexpr RngPurpose kSimRanges = static_cast<RngPurpose>(66);
inline constexpr RngPurpose kSimGoals = static_cast<RngPurpose>(67);

/// A scan with the configured beam layout and no ranges yet.
[[nodiscard]] LaserScan empty_scan(const SimulationConfig& config, double stamp);

/// Fills scan.ranges from the true robot pose: a ray cast per beam plus Gaussian noise,
/// dropouts (max range) and short readings (Thrun et al., table 6.1 / eq. 6.4-6.6: the
/// mixture of hit, short and max components of the beam model).
void simulate_ranges(const RayCaster& caster, const Pose2& truth, const SimulationConfig& config,
                     std::uint64_t scan_index, LaserScan& scan);

/// The odometry increment reported for a true increment `delta` (robot frame) under the noise
/// model of OdometryNoise, drawn from the stream of scan `scan_index`.
[[nodiscard]] Pose2 noisy_increment(const Pose2& delta, const OdometryNoise& noise,
                                    std::uint64_t seed, std::uint64_t scan_index);

/// The odometry increment for a true increment under the motion model's own noise
/// (OdometryAlphaNoise), drawn from the stream of scan `scan_index`.
[[nodiscard]] Pose2 alpha_increment(const Pose2& delta, const OdometryAlphaNoise& noise,
                                    std::uint64_t seed, std::uint64_t scan_index);

}  // namespace mote::sim::detail
