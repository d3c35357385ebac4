// 02: the free-function layer. Drives the engine's kernels by hand on a particle store:
// sample motion, weigh by a custom likelihood, normalize, and resample with a KLD count.
#include <cmath>
#include <cstdio>

#include "mote/engine/estimate.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/motion.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/recovery.hpp"
#include "mote/engine/resample.hpp"
#include "mote/engine/weights.hpp"

int main() {
  const mote::Executor executor(2);
  mote::ParticleStore store;
  const std::uint64_t seed = 7;
  executor([&] {
    mote::initialize_gaussian(store, 100000, {0, 0, 0}, Eigen::Vector3d(0.5, 0.5, 0.1).asDiagonal(),
                              seed);
  });
  const mote::OdometryModel motion{.alpha1 = 0.05, .alpha2 = 0.05, .alpha3 = 0.05, .alpha4 = 0.05};
  mote::KldBins bins({-20, -20, 20, 20}, 0.5, 0.5, 10 * M_PI / 180);
  const mote::KldConfig kld{.min_particles = 1000, .max_particles = 100000};
  for (std::uint64_t step = 1; step <= 5; ++step) {
    executor([&] {
      const mote::Odometry u{{0.0, 0.0, 0.0}, {0.5, 0.0, 0.0}};
      mote::predict(motion, u, store.view(), seed, step);
      // A beacon at (2.5, 0) measured at 2.5 m - 0.5 m * step, sigma 0.1 m.
      const double expected = 2.5 - 0.5 * static_cast<double>(step);
      mote::reweight(store.view(), [&](float x, float y, float) {
        const double r = std::hypot(2.5 - x, y) - expected;
        return -0.5 * r * r / 0.01;
      });
      const mote::NormalizeResult w = mote::normalize(store.view());
      const std::size_t n = mote::kld_sample_count(std::as_const(store).view(), bins, kld);
      mote::resample_systematic(store, n, seed, step);
      const mote::PoseEstimate e = mote::estimate(std::as_const(store).view());
      std::printf("step %llu: ESS %.0f, KLD keeps %zu particles, mean (%.2f, %.2f)\n",
                  static_cast<unsigned long long>(step), w.effective_sample_size, n, e.mean.x,
                  e.mean.y);
    });
  }
  return 0;
}
