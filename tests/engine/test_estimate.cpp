#include "mote/engine/estimate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "mote/engine/executor.hpp"

namespace mote {
namespace {

void set(const ParticleView& p, std::size_t i, const Pose2& pose, double w) {
  p.set_pose(i, pose);
  p.logw[i] = static_cast<float>(std::log(w));
}

TEST(Estimate, WeightedMeanAndCovariance) {
  ParticleStore store(2);
  set(store.view(), 0, {0.0, 0.0, 0.1}, 0.25);
  set(store.view(), 1, {4.0, 2.0, 0.3}, 0.75);
  const PoseEstimate e = estimate(store.view());
  EXPECT_NEAR(e.mean.x, 3.0, 1e-6);
  EXPECT_NEAR(e.mean.y, 1.5, 1e-6);
  // Var of a two-point distribution: w0 w1 d^2.
  EXPECT_NEAR(e.covariance(0, 0), 0.1875 * 16, 1e-5);
  EXPECT_NEAR(e.covariance(0, 1), 0.1875 * 8, 1e-5);
  EXPECT_NEAR(e.covariance(1, 1), 0.1875 * 4, 1e-5);
  EXPECT_EQ(e.count, 2U);
}

TEST(Estimate, HeadingIsACircularMeanWithWrappedResiduals) {
  ParticleStore store(2);
  set(store.view(), 0, {0.0, 0.0, 3.1}, 0.5);
  set(store.view(), 1, {0.0, 0.0, -3.1}, 0.5);
  const PoseEstimate e = estimate(store.view());
  EXPECT_NEAR(std::abs(e.mean.theta), std::numbers::pi, 1e-6);  // not 0
  const double d = std::numbers::pi - 3.1;
  EXPECT_NEAR(e.covariance(2, 2), d * d, 1e-6);
}

TEST(Estimate, IsIndependentOfThreads) {
  ParticleStore store(50001);
  const ParticleView p = store.view();
  for (std::size_t i = 0; i < p.size(); ++i) {
    set(p, i, {std::sin(0.1 * double(i)), std::cos(0.3 * double(i)), 0.001 * double(i)},
        1.0 + 0.5 * std::sin(double(i)));
  }
  PoseEstimate serial;
  PoseEstimate parallel;
  Executor(1)([&] { serial = estimate(p); });
  const Executor ex(4);
  ex([&] { parallel = estimate(p); });
  EXPECT_EQ(serial.mean, parallel.mean);
  EXPECT_EQ(serial.covariance, parallel.covariance);
}

TEST(Cluster, SeparatesBlobsAndPicksTheHeaviest) {
  ParticleStore store(200);
  const ParticleView p = store.view();
  for (std::size_t i = 0; i < 200; ++i) {
    const bool far = i % 2 == 1;
    const double jitter = 0.01 * static_cast<double>(i % 10);
    set(p, i, {far ? 10.0 + jitter : jitter, 1.0, 0.2}, far ? 0.7 : 0.3);
  }
  const std::vector<PoseEstimate> clusters = cluster(p);
  ASSERT_EQ(clusters.size(), 2U);
  EXPECT_NEAR(clusters[0].weight, 0.3, 1e-6);  // ordered by first particle
  EXPECT_NEAR(clusters[1].weight, 0.7, 1e-6);
  const PoseEstimate* best = best_cluster(clusters);
  ASSERT_NE(best, nullptr);
  EXPECT_NEAR(best->mean.x, 10.05, 1e-5);  // odd i: jitter 0.01, 0.03, ..., 0.09
  EXPECT_EQ(best->count, 100U);
  EXPECT_EQ(best_cluster({}), nullptr);
}

// Three blobs 20 m apart, each spread over many bins, their particles interleaved so that every
// block of the summarizer (2048 particles) holds bins of all three and bins recur across
// blocks: the per-block numbering and its merge must still give one cluster per blob, in order
// of first particle, on any thread count.
TEST(Cluster, ManyBlocksKeepBlobsApartInOrderOfFirstParticle) {
  constexpr std::size_t kN = 3 * 7001 + 2;
  ParticleStore store(kN);
  const ParticleView p = store.view();
  const double blob_x[3] = {20.0, 40.0, 0.0};  // not in order of x
  std::size_t count[3] = {};
  double weight[3] = {};
  double sum_x[3] = {};
  for (std::size_t i = 0; i < kN; ++i) {
    const std::size_t b = (i * 7 / 5) % 3;
    const double spread = 0.0013 * static_cast<double>(i % 997);  // up to 1.3 m: many bins
    const double w = 1.0 + 0.5 * std::sin(0.01 * static_cast<double>(i));
    set(p, i, {blob_x[b] + spread, 3.0 - spread, 0.4 * spread}, w);
    ++count[b];
    weight[b] += w;
    sum_x[b] += w * (blob_x[b] + spread);
  }
  const double total = weight[0] + weight[1] + weight[2];
  std::vector<PoseEstimate> serial;
  Executor(1)([&] { serial = cluster(p); });
  ASSERT_EQ(serial.size(), 3U);
  for (std::size_t c = 0; c < 3; ++c) {  // particles 0, 1, 2 are in blobs 0, 1, 2
    const std::size_t b = c;
    EXPECT_EQ(serial[c].count, count[b]) << "cluster " << c;
    EXPECT_NEAR(serial[c].weight, weight[b] / total, 1e-9);
    EXPECT_NEAR(serial[c].mean.x, sum_x[b] / weight[b], 1e-4);
  }
  std::vector<PoseEstimate> parallel;
  const Executor ex(4);
  ex([&] { parallel = cluster(p); });
  ASSERT_EQ(parallel.size(), serial.size());
  for (std::size_t c = 0; c < serial.size(); ++c) {
    EXPECT_EQ(parallel[c].mean, serial[c].mean);
    EXPECT_EQ(parallel[c].covariance, serial[c].covariance);
    EXPECT_EQ(parallel[c].count, serial[c].count);
  }
}

// Occupied cells of a 96 x 96 grid of 0.5 m bins at density 0.35 (below percolation: clusters of
// every size and shape, many of them), two particles per cell at its centre in a shuffled order.
// The clusters must be the 8-connected components of the cells, in order of first particle, on
// 1 and 4 threads.
TEST(Cluster, MatchesConnectedComponentsOfARandomGrid) {
  constexpr int kSide = 96;
  std::mt19937_64 rng(7);
  std::vector<int> cells;
  for (int c = 0; c < kSide * kSide; ++c) {
    if (std::uniform_real_distribution<>(0.0, 1.0)(rng) < 0.35) cells.push_back(c);
  }
  std::vector<int> order;
  for (const int c : cells) order.insert(order.end(), {c, c});
  std::shuffle(order.begin(), order.end(), rng);
  // Reference: breadth-first search over the occupied cells; component ids by first particle.
  std::vector<int> component(kSide * kSide, -1);
  std::vector<std::size_t> expected_count;
  for (const int start : order) {
    if (component[static_cast<std::size_t>(start)] >= 0) continue;
    const int id = static_cast<int>(expected_count.size());
    expected_count.push_back(0);
    std::vector<int> queue{start};
    component[static_cast<std::size_t>(start)] = id;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int cx = queue[head] % kSide;
      const int cy = queue[head] / kSide;
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const int nx = cx + dx;
          const int ny = cy + dy;
          if (nx < 0 || ny < 0 || nx >= kSide || ny >= kSide) continue;
          const auto n = static_cast<std::size_t>(ny * kSide + nx);
          if (component[n] != -1 || !std::binary_search(cells.begin(), cells.end(), int(n))) {
            continue;
          }
          component[n] = id;
          queue.push_back(static_cast<int>(n));
        }
      }
    }
  }
  for (const int c : order) {
    ++expected_count[static_cast<std::size_t>(component[static_cast<std::size_t>(c)])];
  }
  ASSERT_GT(expected_count.size(), 64U);  // past the summarizer's per-block cluster sums

  // Once as it is, and with a last particle 1 km away (its own cluster, and a bounding box too
  // large for the labelling's dense bin array: the bitmap in front of the hash map runs) or
  // 100 km away (a box too large for the bitmap too: the hash map alone).
  for (const double far : {0.0, 1.0e3, 1.0e5}) {
    const bool far_particle = far > 0.0;
    ParticleStore store(order.size() + (far_particle ? 1 : 0));
    const ParticleView p = store.view();
    for (std::size_t i = 0; i < order.size(); ++i) {
      set(p, i, {0.5 * (order[i] % kSide) + 0.25, 0.5 * (order[i] / kSide) + 0.25, 0.05}, 1.0);
    }
    std::vector<std::size_t> expected = expected_count;
    if (far_particle) {
      set(p, order.size(), {far, 0.25, 0.05}, 1.0);
      expected.push_back(1);
    }
    for (const int threads : {1, 4}) {
      std::vector<PoseEstimate> clusters;
      const Executor ex(threads);
      ex([&] { clusters = cluster(p); });
      ASSERT_EQ(clusters.size(), expected.size()) << threads << " threads, far " << far;
      for (std::size_t c = 0; c < clusters.size(); ++c) {
        ASSERT_EQ(clusters[c].count, expected[c]) << "cluster " << c << ", " << threads;
      }
    }
  }
}

TEST(Cluster, ConnectsAcrossTheThetaWrapAndHonoursConnectivity) {
  ParticleStore store(3);
  const ParticleView p = store.view();
  set(p, 0, {1.0, 1.0, std::numbers::pi - 0.01}, 1.0);
  set(p, 1, {1.0, 1.0, -std::numbers::pi + 0.01}, 1.0);  // neighbouring bin across the wrap
  set(p, 2, {1.0, 1.0, 0.0}, 1.0);                       // same place, opposite heading
  EXPECT_EQ(cluster(p).size(), 2U);                      // 26-connectivity
  ClusterConfig xy;
  xy.connectivity = Connectivity::k8;
  EXPECT_EQ(cluster(p, xy).size(), 1U);  // headings ignored
}

}  // namespace
}  // namespace mote
