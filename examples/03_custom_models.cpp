// 03: plugging in your own models. A motion model and a sensor model only have to satisfy
// mote::MotionModel and mote::SensorModel; mote::predict and mote::weigh_scan then run them in
// parallel with the same determinism guarantees as the built-in ones.
#include <cmath>
#include <cstdio>

#include "mote/engine/estimate.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/motion.hpp"
#include "mote/engine/recovery.hpp"
#include "mote/engine/sensor_model.hpp"

// Constant drift plus isotropic Gaussian noise (sigma metres per update).
struct DriftModel {
  float vx = 0.1F;
  float sigma = 0.02F;
  void sample(const mote::Odometry&, const mote::ParticleView& p, std::size_t begin,
              std::size_t end, const mote::RngStream& rng) const {
    for (std::size_t i = begin; i < end; ++i) {
      const auto n = rng.normal4(static_cast<std::uint32_t>(i));
      p.x[i] += vx + sigma * n[0];
      p.y[i] += sigma * n[1];
    }
  }
};
static_assert(mote::MotionModel<DriftModel>);

// A range-only sensor: the first beam's range is the distance to a wall at x = wall_x.
struct WallRangeModel {
  float wall_x = 5.0F;
  float sigma = 0.05F;
  void weigh(const mote::BeamSet& beams, const mote::ParticleView& p, std::size_t begin,
             std::size_t end) const {
    for (std::size_t i = begin; i < end; ++i) {
      const float r = (wall_x - p.x[i]) - beams.range[0];
      p.logw[i] += -0.5F * r * r / (sigma * sigma);
    }
  }
};
static_assert(mote::SensorModel<WallRangeModel>);

int main() {
  const mote::Executor executor;  // every core
  mote::ParticleStore store;
  executor([&] {
    mote::initialize_gaussian(store, 50000, {0, 0, 0}, Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal(),
                              /*seed=*/1);
    mote::BeamSet beams;
    beams.angle = {0.0F};
    beams.range = {4.2F};  // the robot is 0.8 m from the start, 4.2 m from the wall
    mote::predict(DriftModel{}, {}, store.view(), /*seed=*/1, /*step=*/1);
    mote::weigh_scan(WallRangeModel{}, beams, store.view());
    (void)mote::normalize(store.view());
  });
  const mote::PoseEstimate e = mote::estimate(std::as_const(store).view());
  std::printf("x = %.3f m (expected 0.8), std %.3f m\n", e.mean.x, std::sqrt(e.covariance(0, 0)));
  return std::abs(e.mean.x - 0.8) < 0.05 ? 0 : 1;
}
