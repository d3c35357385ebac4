#pragma once
/// \file
/// Point estimates from the particle set: the weighted mean (circular mean for the heading) and
/// covariance, and clusters of connected occupied histogram bins (as ROS amcl reports them).

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <numbers>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/engine/chunks.hpp"
#include "mote/engine/particles.hpp"

namespace mote {

/// A weighted Gaussian summary of (part of) the particle set.
struct PoseEstimate {
  Pose2 mean;  ///< weighted mean; theta = atan2(sum w sin, sum w cos) (circular mean)
  /// Weighted covariance over (x m, y m, theta rad), theta residuals wrapped to (-pi, pi].
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double weight = 0.0;    ///< total normalized weight (1 for the whole set)
  std::size_t count = 0;  ///< number of particles
};

/// Weighted mean and covariance of the whole set (weights exp(logw), renormalized; NaN and
/// -inf weigh 0). Sums over a fixed block grid: bit-identical for any thread count. A set
/// without positive weight gives count 0.
[[nodiscard]] PoseEstimate estimate(const ConstParticleView& particles);

/// How histogram bins connect into clusters.
enum class Connectivity {
  k8,   ///< neighbours in (x, y) only: headings are ignored when forming clusters
  k26,  ///< neighbours in (x, y, theta), theta bins wrapping around (amcl's kd-tree clusters)
};

/// Clustering parameters (bin sizes as amcl's kd-tree: 0.5 m, 0.5 m, 10 degrees).
struct ClusterConfig {
  double bin_x = 0.5;                                ///< m
  double bin_y = 0.5;                                ///< m
  double bin_theta = 10.0 * std::numbers::pi / 180;  ///< rad
  Connectivity connectivity = Connectivity::k26;
};

/// Groups particles into clusters of connected occupied bins and summarizes each; clusters are
/// ordered by their first particle index, so the output is deterministic. O(N): parallel passes
/// for weights, bin keys, bin numbers within blocks, cluster labels (union-find) and moments; one
/// serial merge of the blocks' distinct bins (a flat hash map).
[[nodiscard]] std::vector<PoseEstimate> cluster(const ConstParticleView& particles,
                                                const ClusterConfig& config = {});

/// The whole-set estimate and the clusters of one particle set.
struct ParticleSummary {
  PoseEstimate overall;                ///< as estimate()
  std::vector<PoseEstimate> clusters;  ///< as cluster(): ordered by first particle
};

/// estimate() and cluster() in one go, sharing the weights and moments between the two and
/// keeping its scratch memory (per-particle weights, bin keys and numbers) between calls: what
/// the Localizer runs once per update. Runs in the caller's task arena; bit-identical results for
/// any thread count (sums over a fixed block grid, bins numbered in particle order).
class PoseSummarizer {
 public:
  explicit PoseSummarizer(const ClusterConfig& config = {});
  ~PoseSummarizer();
  PoseSummarizer(PoseSummarizer&&) noexcept;
  PoseSummarizer& operator=(PoseSummarizer&&) noexcept;

  /// Summarizes `particles`; the clusters are left empty when with_clusters is false.
  const ParticleSummary& operator()(const ConstParticleView& particles, bool with_clusters = true);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The heaviest cluster, or nullptr when there is none.
[[nodiscard]] const PoseEstimate* best_cluster(const std::vector<PoseEstimate>& clusters) noexcept;

}  // namespace mote
