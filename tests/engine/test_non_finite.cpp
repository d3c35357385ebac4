// Non-finite particle columns (x, y, theta, logw = NaN, +inf, -inf) through every kernel of an
// update: nothing crashes or reads out of bounds, and wherever the answer is defined it is not
// NaN (issue 14, item 4). Run it under -DMOTE_SANITIZE="address;undefined" (float-cast-overflow
// included): the float-to-int conversions in the binning and fast math were the hazard.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "mote/engine/beam_model.hpp"
#include "mote/engine/estimate.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/likelihood_field_model.hpp"
#include "mote/engine/motion.hpp"
#include "mote/engine/recovery.hpp"
#include "mote/engine/resample.hpp"
#include "mote/engine/weights.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::size_t kParticles = 203;  // not a multiple of any block or vector width

// A 4 x 4 m room of 5 cm cells with walls around it.
OccupancyGrid room() {
  constexpr int kSize = 80;
  std::vector<CellState> cells(kSize * kSize, CellState::kFree);
  for (int j = 0; j < kSize; ++j) {
    for (int i = 0; i < kSize; ++i) {
      if (i < 2 || j < 2 || i >= kSize - 2 || j >= kSize - 2) {
        cells[static_cast<std::size_t>(j * kSize + i)] = CellState::kOccupied;
      }
    }
  }
  return {kSize, kSize, 0.05, Pose2{}, std::move(cells)};
}

// Which column of particle i holds a non-finite value, and which value: every column gets
// NaN, +inf and -inf; a third of the particles stay finite.
struct Poison {
  int column;  // 0 x, 1 y, 2 theta, 3 logw, -1 none
  float value;
};

Poison poison_of(std::size_t i) {
  if (i % 3 == 0) return {-1, 0.0F};
  const float values[] = {kNaN, kInf, -kInf};
  return {static_cast<int>((i / 3) % 4), values[(i / 9) % 3]};
}

bool pose_finite(const ConstParticleView& p, std::size_t i) {
  return std::isfinite(p.x[i]) && std::isfinite(p.y[i]) && std::isfinite(p.theta[i]);
}

// A store whose finite particles sit inside the room.
ParticleStore poisoned_store() {
  ParticleStore store(kParticles);
  const ParticleView p = store.view();
  for (std::size_t i = 0; i < kParticles; ++i) {
    p.x[i] = 0.5F + 0.01F * static_cast<float>(i % 250);
    p.y[i] = 2.0F;
    p.theta[i] = 0.1F * static_cast<float>(i % 60) - 3.0F;
    p.logw[i] = -std::log(static_cast<float>(kParticles));
    const Poison poison = poison_of(i);
    float* columns[] = {p.x, p.y, p.theta, p.logw};
    if (poison.column >= 0) columns[poison.column][i] = poison.value;
  }
  return store;
}

BeamSet beams() {
  BeamSet b;
  for (int k = 0; k < 12; ++k) {
    b.angle.push_back(-3.0F + 0.5F * static_cast<float>(k));
    b.range.push_back(k % 4 == 3 ? 8.0F : 1.0F + 0.1F * static_cast<float>(k));
  }
  b.range_min = 0.1F;
  b.range_max = 8.0F;
  b.readings = b.valid = b.size();
  return b;
}

template <class Model>
void expect_prediction_keeps_finite_particles_finite(const Model& model) {
  ParticleStore store = poisoned_store();
  const Odometry u{{1.0, 2.0, 0.3}, {1.3, 2.1, 0.5}};
  predict(model, u, store.view(), 7, 1);
  const ConstParticleView p = std::as_const(store).view();
  for (std::size_t i = 0; i < kParticles; ++i) {
    if (poison_of(i).column == -1 || poison_of(i).column == 3) {
      EXPECT_TRUE(pose_finite(p, i)) << "particle " << i;
    }
  }
}

TEST(NonFiniteColumns, PredictKeepsFiniteParticlesFinite) {
  expect_prediction_keeps_finite_particles_finite(OdometryModel{});
  expect_prediction_keeps_finite_particles_finite(OmniModel{});
  expect_prediction_keeps_finite_particles_finite(AckermannModel{});
}

template <class Model>
void expect_weights_finite_where_defined(Model& model) {
  ParticleStore store = poisoned_store();
  const BeamSet b = beams();
  if constexpr (requires { model.prepare(b); }) model.prepare(b);
  weigh_scan(model, b, store.view());
  const ConstParticleView p = std::as_const(store).view();
  for (std::size_t i = 0; i < kParticles; ++i) {
    if (poison_of(i).column == -1) {
      EXPECT_FALSE(std::isnan(p.logw[i])) << "particle " << i;
    }
  }
}

TEST(NonFiniteColumns, BothSensorModelsWeighFiniteParticles) {
  const OccupancyGrid map = room();
  LikelihoodFieldModel field(map, {});
  expect_weights_finite_where_defined(field);
  BeamModel beam(map, {});
  expect_weights_finite_where_defined(beam);
}

TEST(NonFiniteColumns, NormalizeLeavesNoNaN) {
  ParticleStore store = poisoned_store();
  const ParticleView p = store.view();
  // +inf log-weights make the set degenerate (reset to uniform); without them normalize works.
  for (std::size_t i = 0; i < kParticles; ++i) {
    if (p.logw[i] == kInf) p.logw[i] = 0.0F;
  }
  EXPECT_TRUE(normalize(p).ok());
  for (std::size_t i = 0; i < kParticles; ++i) EXPECT_FALSE(std::isnan(p.logw[i])) << i;
  ParticleStore with_inf = poisoned_store();
  EXPECT_EQ(normalize(with_inf.view()).status, WeightStatus::kDegenerate);
  for (std::size_t i = 0; i < kParticles; ++i) EXPECT_TRUE(std::isfinite(with_inf.view().logw[i]));
}

TEST(NonFiniteColumns, KldCountAndResamplingStayInBounds) {
  ParticleStore store = poisoned_store();
  KldBins bins({0.0, 0.0, 4.0, 4.0}, 0.5, 0.5, 0.2);
  const std::size_t k = bins.count(std::as_const(store).view());
  EXPECT_GE(k, 1U);
  EXPECT_LE(k, bins.nx() * bins.ny() * bins.ntheta());
  (void)normalize(store.view());
  resample_systematic(store, 150, 3, 1);
  ASSERT_EQ(store.size(), 150U);
  const ConstParticleView p = std::as_const(store).view();
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_TRUE(std::isfinite(p.logw[i])) << i;
}

TEST(NonFiniteColumns, EstimatesIgnoreParticlesWithoutWeight) {
  ParticleStore store = poisoned_store();
  const ParticleView p = store.view();
  // Non-finite poses carry no weight (NaN or -inf log-weight): the estimate is defined.
  for (std::size_t i = 0; i < kParticles; ++i) {
    if (!pose_finite(std::as_const(store).view(), i)) p.logw[i] = i % 2 == 0 ? kNaN : -kInf;
    if (p.logw[i] == kInf) p.logw[i] = 0.0F;
  }
  const PoseEstimate e = estimate(std::as_const(store).view());
  EXPECT_TRUE(is_finite(e.mean));
  EXPECT_TRUE(e.covariance.allFinite());
  PoseSummarizer summarize;
  const ParticleSummary& s = summarize(std::as_const(store).view());
  EXPECT_TRUE(is_finite(s.overall.mean));
  for (const PoseEstimate& c : s.clusters) {
    if (c.weight > 0.0) {
      EXPECT_TRUE(is_finite(c.mean));
    }
  }
  // And with weight on non-finite poses: no crash, whatever the (undefined) mean is.
  ParticleStore raw = poisoned_store();
  (void)estimate(std::as_const(raw).view());
  (void)summarize(std::as_const(raw).view());
}

// Free space: the room's interior.
class RoomInterior : public FreeSpace {
 public:
  [[nodiscard]] std::size_t free_cell_count() const noexcept override { return 1; }
  [[nodiscard]] Point2 free_point(std::size_t, double u, double v) const noexcept override {
    return {0.5 + 3.0 * u, 0.5 + 3.0 * v};
  }
  [[nodiscard]] Bounds2 bounds() const noexcept override { return {0.0, 0.0, 4.0, 4.0}; }
};

TEST(NonFiniteColumns, InjectionReplacesParticlesWithFinitePoses) {
  ParticleStore store = poisoned_store();
  const RoomInterior space;
  EXPECT_EQ(inject_random_particles(store.view(), 1.0, space, 5, 2), kParticles);
  const ConstParticleView p = std::as_const(store).view();
  for (std::size_t i = 0; i < kParticles; ++i) EXPECT_TRUE(pose_finite(p, i)) << i;
  ParticleStore half = poisoned_store();
  (void)inject_random_particles(half.view(), 0.5, space, 5, 2);
}

}  // namespace
}  // namespace mote
