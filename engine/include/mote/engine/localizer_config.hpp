#pragma once
/// \file
/// Every parameter of mote::Localizer, with units and defaults. Names follow ROS amcl (and
/// nav2_amcl) where they overlap, with the same defaults as nav2_amcl; the differences are listed
/// in README.md
/// ("Differences from amcl").

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace mote {

/// Which measurement model weights the particles.
enum class LaserModel : std::uint8_t {
  kLikelihoodField,  ///< Thrun table 6.3 over a precomputed distance field (amcl
                     ///< "likelihood_field")
  kBeam,             ///< Thrun table 6.1 with ray-cast expected ranges (amcl "beam")
};

/// How the likelihood-field model combines beams.
enum class LikelihoodCombination : std::uint8_t {
  kProduct,      ///< the textbook product, summed in the log domain (Thrun table 6.3)
  kAmclCubedSum  ///< ROS amcl's heuristic p = 1 + sum(pz^3), for amcl compatibility
};

/// Which motion model samples the particles forward.
enum class OdomModel : std::uint8_t {
  kDiff,       ///< odometry model, Thrun table 5.6 (alpha1..alpha4)
  kOmni,       ///< holonomic: adds amcl's alpha5 strafe noise
  kAckermann,  ///< car-like bicycle model (wheelbase, steering limited)
};

/// Parameters of the Localizer. Units: metres, radians, seconds.
struct LocalizerConfig {
  // --- particles and KLD adaptation (Fox 2003) -------------------------------------------
  int min_particles = 500;   ///< lower bound of the KLD-adaptive count
  int max_particles = 2000;  ///< upper bound (and the count after initialization)
  double pf_err = 0.05;      ///< KLD epsilon: max K-L divergence between sample and true posterior
  /// KLD confidence. With kld_z_is_quantile false (mote's default) it is the probability 1 - delta
  /// whose standard-normal quantile enters Fox's formula; true reads it as that quantile itself,
  /// as ROS amcl's code does (pf_z 0.99 then means z = 0.99, a far looser bound).
  double pf_z = 0.99;
  bool kld_z_is_quantile = false;
  double kld_bin_xy = 0.5;                    ///< m, KLD histogram bin edge in x and y
  double kld_bin_theta = 0.1745329251994330;  ///< rad (10 degrees), KLD bin edge in heading

  // --- resampling and recovery (Thrun table 8.3) -------------------------------------------
  int resample_interval = 1;           ///< filter updates between resampling opportunities
  double resample_ess_fraction = 0.5;  ///< resample only when ESS < fraction * N (1 = always)
  double recovery_alpha_slow = 0.0;    ///< w_slow smoothing rate; 0 disables injection (amcl)
  double recovery_alpha_fast = 0.0;    ///< w_fast smoothing rate (Thrun suggests 0.1 with 0.001)

  // --- update gate ---------------------------------------------------------------------------
  double update_min_d = 0.25;  ///< m of translation before the filter updates
  double update_min_a = 0.2;   ///< rad of rotation before the filter updates
  /// m: an odometry step longer than this between two updates is taken as an odometry reset
  /// (a driver restart, a log splice), not as motion: the update is rejected
  /// (kRejectedOdometry), the particles stay, and later steps count from the new pose.
  double odom_jump_max_d = 10.0;

  // --- motion model (Thrun table 5.6, amcl alpha convention) ------------------------------
  OdomModel odom_model_type = OdomModel::kDiff;
  bool amcl_motion_conventions = true;  ///< amcl's backward motion and rot1 = 0 below 1 cm
  double alpha1 = 0.2;                  ///< rotation noise from rotation
  double alpha2 = 0.2;                  ///< rotation noise from translation
  double alpha3 = 0.2;                  ///< translation noise from translation
  double alpha4 = 0.2;                  ///< translation noise from rotation
  double alpha5 = 0.2;                  ///< strafe noise from translation (omni only)
  double wheelbase = 0.5;               ///< m, Ackermann only

  // --- sensor model (Thrun tables 6.1, 6.3) -----------------------------------------------
  LaserModel laser_model_type = LaserModel::kLikelihoodField;
  LikelihoodCombination likelihood_combination = LikelihoodCombination::kProduct;
  int max_beams = 60;                      ///< beams used per scan, evenly spaced over valid ones
  double laser_min_range = -1.0;           ///< m; < 0 uses the scan's range_min
  double laser_max_range = 100.0;          ///< m; < 0 uses the scan's range_max
  double z_hit = 0.5;                      ///< mixture weight of the measurement Gaussian
  double z_short = 0.05;                   ///< mixture weight of unexpected obstacles (beam)
  double z_max = 0.05;                     ///< mixture weight of max-range readings
  double z_rand = 0.5;                     ///< mixture weight of random readings
  double sigma_hit = 0.2;                  ///< m, std. dev. of the measurement Gaussian
  double lambda_short = 0.1;               ///< 1/m, rate of the short-reading exponential (beam)
  double laser_likelihood_max_dist = 2.0;  ///< m, distance field clamp (likelihood field)
  /// Likelihood exponent tau applied to each scan's log-likelihood (tempering for correlated
  /// beams; MRPT's powFactor). 1 is the plain product of beam likelihoods.
  double likelihood_tempering = 1.0;
  bool unknown_cells_block_rays = true;  ///< beam model: unknown cells stop rays (amcl)

  // --- execution -----------------------------------------------------------------------------
  int threads = 0;           ///< worker threads; 0 = every core
  std::uint64_t seed = 42;   ///< random seed; same seed + input = same output
  std::size_t grain = 4096;  ///< particles per parallel task (results never depend on it)

  /// Throws ConfigError naming the first parameter out of its valid range.
  void validate() const;
};

/// A configuration read from a file, with the warnings it produced (unknown keys).
struct LoadedConfig {
  LocalizerConfig config;
  std::vector<std::string> warnings;
};

/// Reads a LocalizerConfig from YAML: either a flat map of the fields above (amcl names), or a
/// nav2 params file as it is (the `amcl: ros__parameters:` section is used). Keys absent from the
/// file keep their defaults; unknown keys give a warning naming them; a wrong type or an
/// out-of-range value throws InputError naming the file and key.
[[nodiscard]] LoadedConfig load_config(const std::filesystem::path& yaml);

/// As load_config, from YAML text; `name` stands for the file in messages.
[[nodiscard]] LoadedConfig parse_config(const std::string& yaml_text, const std::string& name);

}  // namespace mote
