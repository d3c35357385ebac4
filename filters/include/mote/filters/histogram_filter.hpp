#pragma once
/// \file
/// Histogram filters, the exact members of the Bayes filter family on a discrete state space:
/// the discrete Bayes filter (Thrun et al., Probabilistic Robotics, table 4.1) over K states with
/// an explicit transition matrix, and grid localization (section 8.2, table 8.1) over a
/// discretized (x, y, theta) on an occupancy grid, whose motion update is a convolution with the
/// odometry model's kernel and whose measurement update is the likelihood-field model. They are
/// the oracles the particle filter is checked against on small worlds.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/engine/beams.hpp"
#include "mote/engine/likelihood_field_model.hpp"
#include "mote/engine/motion.hpp"
#include "mote/engine/particles.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote {

/// Thrun table 4.1 over states 0..K-1. Throws ConfigError on a shape mismatch, a negative or
/// non-finite probability, a transition column that does not sum to 1, or a measurement that
/// every state with positive belief rules out.
class DiscreteBayesFilter {
 public:
  /// Starts from `belief` (non-negative, positive sum; normalized here).
  explicit DiscreteBayesFilter(Eigen::VectorXd belief);
  /// The uniform belief over k states.
  [[nodiscard]] static DiscreteBayesFilter uniform(std::size_t k);

  /// Line 3: bel_bar(x_k) = sum_i p(x_k | u, x_i) bel(x_i), transition(k, i) = p(x_k | u, x_i)
  /// (every column a distribution).
  void predict(const Eigen::MatrixXd& transition);
  /// Line 4: bel(x_k) = eta p(z | x_k) bel_bar(x_k), likelihood(k) = p(z | x_k). Returns
  /// log p(z) = log sum_k p(z | x_k) bel_bar(x_k).
  double correct(const Eigen::VectorXd& likelihood);

  [[nodiscard]] const Eigen::VectorXd& belief() const noexcept { return belief_; }

 private:
  Eigen::VectorXd belief_;
};

/// Grid localization parameters.
struct GridLocalizationConfig {
  int cell_stride = 1;  ///< map cells per state cell along x and y (>= 1)
  int headings = 36;    ///< heading bins over [-pi, pi) (>= 1)
  /// Points per axis at which the motion density is averaged over a destination cell (>= 1).
  int subsamples = 3;
  double kernel_sigmas = 3.0;  ///< motion kernel window half-width, standard deviations
  OdometryModel motion;        ///< its density (Thrun table 5.5) is the motion kernel
  LikelihoodFieldParams sensor;
};

/// One entry of a motion kernel: probability that a pose in heading bin `from` moves by
/// (di, dj) cells and into heading bin `to`.
struct MotionKernelEntry {
  int di = 0;
  int dj = 0;
  int from = 0;
  int to = 0;
  double p = 0.0;
};

/// The motion kernel of one odometry step, grouped by destination heading (by_to[t]); for every
/// source heading the entries' p sum to 1.
struct MotionKernel {
  std::vector<std::vector<MotionKernelEntry>> by_to;
};

/// Grid localization (Thrun table 8.1) over (i, j, t): i, j state cells of cell_stride map
/// cells, t heading bins centred on -pi + (t + 1/2) 2 pi / headings. State index
/// (t * ny + j) * nx + i. Memory: 8 bytes of belief, 8 of scratch, 4 of log-likelihood and 32
/// of cell-centre particles (two buffers of x, y, theta, logw) per state.
class GridLocalization {
 public:
  /// Throws ConfigError on invalid parameters. The belief starts uniform over free cells.
  GridLocalization(const OccupancyGrid& grid, const GridLocalizationConfig& config);

  [[nodiscard]] int nx() const noexcept { return nx_; }
  [[nodiscard]] int ny() const noexcept { return ny_; }
  [[nodiscard]] int headings() const noexcept { return nt_; }
  [[nodiscard]] std::size_t state_count() const noexcept { return belief_.size(); }
  [[nodiscard]] double cell_size() const noexcept { return cell_; }  ///< m

  /// The centre pose of state k (map frame).
  [[nodiscard]] Pose2 state_pose(std::size_t k) const noexcept;
  /// The state holding a pose, or npos when it is off the grid.
  [[nodiscard]] std::size_t state_of(const Pose2& pose) const noexcept;
  /// Whether the map cell under state k's centre is free.
  [[nodiscard]] bool is_free(std::size_t k) const noexcept { return free_[k % plane()] != 0; }
  static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();

  /// Uniform over the states whose cell is free.
  void set_uniform();
  /// Sets the belief (state_count() non-negative values with a positive sum; normalized).
  void set_belief(std::vector<double> belief);

  /// The motion kernel of odometry step u (Thrun table 5.5 density, averaged over
  /// subsamples^3 points of each destination cell, times the Jacobian 1/trans of the change
  /// from (rot1, trans, rot2) to (x, y, theta); normalized per source heading).
  [[nodiscard]] MotionKernel motion_kernel(const Odometry& u) const;
  /// Table 8.1, line 3: bel_bar = kernel * bel, parallel over output rows (deterministic).
  /// Mass moved off the grid is dropped and the result renormalized.
  void predict(const MotionKernel& kernel);
  void predict(const Odometry& u) { predict(motion_kernel(u)); }

  /// log p(z | state) from the likelihood-field model at every state's centre pose, in
  /// parallel; -inf for states whose cell is not free (the robot is never inside an obstacle).
  [[nodiscard]] std::vector<float> measurement_log_likelihood(const BeamSet& beams);
  /// Table 8.1, line 4: bel = eta exp(loglik) bel_bar. Returns log sum exp(loglik) bel_bar.
  /// Throws ConfigError when no state with belief explains the measurement.
  double correct(const std::vector<float>& log_likelihood);
  double correct(const BeamSet& beams) { return correct(measurement_log_likelihood(beams)); }

  [[nodiscard]] std::span<const double> belief() const noexcept { return belief_; }
  /// The belief summed over headings: nx * ny values, row-major from j = 0.
  [[nodiscard]] std::vector<double> marginal_xy() const;

 private:
  [[nodiscard]] std::size_t plane() const noexcept {
    return static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  }
  [[nodiscard]] double heading_of(int t) const noexcept;
  [[nodiscard]] std::vector<MotionKernelEntry> kernel_from(int from, const Odometry& u) const;
  void normalize_belief(const char* where);

  Pose2 origin_;  // the grid's lower-left corner and yaw
  double cos_yaw_, sin_yaw_;
  GridLocalizationConfig config_;
  int nx_, ny_, nt_;
  double cell_;
  std::vector<unsigned char> free_;  // per (i, j)
  std::vector<double> belief_;
  std::vector<double> next_;
  ParticleStore centres_;  // one particle per state at its centre pose, for the sensor model
  LikelihoodFieldModel sensor_;
};

}  // namespace mote
