#pragma once
/// \file
/// Motion models (Thrun et al., Probabilistic Robotics, chapter 5) and the parallel predict
/// kernel. A model samples x_t ~ p(x_t | u_t, x_{t-1}) for a chunk of particles; predict runs it
/// over the whole set with per-particle Philox streams, so the result is bit-identical for any
/// thread count and grain (design.md section 3). Plug your own model through MotionModel.

#include <concepts>
#include <cstddef>
#include <cstdint>

#include "mote/core/pose.hpp"
#include "mote/engine/chunks.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/philox.hpp"

namespace mote {

/// Odometry input u_t: the odometry frame's pose at the previous and at the current update.
struct Odometry {
  Pose2 previous;  ///< odometry pose at t-1 (m, rad)
  Pose2 current;   ///< odometry pose at t (m, rad)
};

/// A motion model: sample(u, particles, begin, end, rng) moves particles [begin, end) in place,
/// drawing particle i's noise only from rng.normal4(i, ...) / rng.uniform4(i, ...). end may reach
/// particles.padded_size(); padding lanes hold finite values and may be moved like particles.
template <class M>
concept MotionModel = requires(const M& model, const Odometry& u, const ParticleView& particles,
                               std::size_t begin, std::size_t end, const RngStream& rng) {
  { model.sample(u, particles, begin, end, rng) } -> std::same_as<void>;
};

/// Thrun's odometry model (table 5.6) with noise parameters alpha1..alpha4 as in ROS amcl:
/// variance of rot = alpha1 rot^2 + alpha2 trans^2, of trans = alpha3 trans^2 + alpha4 (rot1^2 +
/// rot2^2).
struct OdometryModel {
  double alpha1 = 0.2;  ///< rad^2/rad^2: rotation noise from rotation
  double alpha2 = 0.2;  ///< rad^2/m^2: rotation noise from translation
  double alpha3 = 0.2;  ///< m^2/m^2: translation noise from translation
  double alpha4 = 0.2;  ///< m^2/rad^2: translation noise from rotation
  /// ROS amcl conventions: rot1 = 0 when the translation is under 1 cm (no heading from a tiny
  /// displacement), and rotation noise uses min(|rot|, |pi - rot|) so that driving backwards
  /// is not mistaken for two half turns.
  bool amcl_compatible = true;

  void sample(const Odometry& u, const ParticleView& particles, std::size_t begin, std::size_t end,
              const RngStream& rng) const;
};

/// ROS amcl's omnidirectional model: translation along the odometry bearing, a lateral
/// (strafe) term with variance alpha1 rot^2 + alpha5 trans^2, and rotation.
struct OmniModel {
  double alpha1 = 0.2;  ///< rad^2/rad^2: rotation noise from rotation (and strafe from rotation)
  double alpha2 = 0.2;  ///< rad^2/m^2: rotation noise from translation
  double alpha3 = 0.2;  ///< m^2/m^2: translation noise from translation
  double alpha4 = 0.2;  ///< m^2/rad^2: rotation noise from rotation (amcl's rot variance term)
  double alpha5 = 0.1;  ///< m^2/m^2: strafe noise from translation

  void sample(const Odometry& u, const ParticleView& particles, std::size_t begin, std::size_t end,
              const RngStream& rng) const;
};

/// A car-like (Ackermann) robot as a kinematic bicycle with wheelbase L. The odometry
/// increment in the previous body frame, (dx, dy, dtheta), is read as one circular arc: arc
/// length s = chord * (dtheta/2) / sin(dtheta/2), signed by the direction of travel, and
/// steering angle phi = atan(L dtheta / s). Each particle perturbs s and phi, then follows its
/// own arc exactly: dtheta' = s' tan(phi') / L, chord = s' sinc(dtheta'/2), moved along the
/// mid-arc heading theta + dtheta'/2. A car cannot strafe, so there is no lateral noise term.
struct AckermannModel {
  double wheelbase = 0.33;       ///< m, rear axle to front axle (L)
  double alpha_distance = 0.05;  ///< m^2/m^2: variance of s per s^2
  double alpha_steering = 0.05;  ///< rad^2/rad^2: variance of phi per phi^2
  double steering_floor = 1e-4;  ///< rad^2: variance of phi when driving straight
  double max_steering = 0.6;     ///< rad: |phi| is clamped to this

  void sample(const Odometry& u, const ParticleView& particles, std::size_t begin, std::size_t end,
              const RngStream& rng) const;
};

static_assert(MotionModel<OdometryModel> && MotionModel<OmniModel> && MotionModel<AckermannModel>);

/// One circular arc of the bicycle model: signed length (m, negative when reversing) and
/// steering angle (rad).
struct AckermannArc {
  double length = 0.0;
  double steering = 0.0;
};

/// The arc AckermannModel reads an increment (dx, dy, dtheta) in the previous body frame as:
/// s = chord * (dtheta/2) / sin(dtheta/2), signed by dx, and phi = atan(L dtheta / s), clamped
/// to +-max_steering (0 when s is 0).
[[nodiscard]] AckermannArc ackermann_arc(const Pose2& increment, double wheelbase,
                                         double max_steering) noexcept;

/// Moves every particle (and padding lane) by model, with randomness keyed by (seed, step,
/// particle index, RngPurpose::kMotion). Runs in the current task arena (mote::Executor).
template <MotionModel M>
void predict(const M& model, const Odometry& u, const ParticleView& particles, std::uint64_t seed,
             std::uint64_t step, std::size_t grain = kDefaultGrain) {
  const RngStream rng{seed, step, RngPurpose::kMotion};
  for_each_particle_chunk(particles.padded_size(), grain, [&](std::size_t begin, std::size_t end) {
    model.sample(u, particles, begin, end, rng);
  });
}

}  // namespace mote
