#pragma once
/// \file
/// Every parameter of mote::Localizer, with units and defaults. Names follow ROS amcl (and
/// nav2_amcl) where they overlap. The defaults are mote's own: mechanisms that adapt to the
/// sensor and map (adaptive tempering, recovery, a global set sized to the map) instead of
/// nav2's constants; nav2_defaults() gives nav2_amcl's values. The differences are listed in
/// docs/configuration.md ("Differences from amcl").

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mote {

/// Which measurement model weights the particles.
enum class LaserModel : std::uint8_t {
  kLikelihoodField,  ///< Thrun table 6.3 over a precomputed distance field (amcl
                     ///< "likelihood_field")
  kBeam,             ///< Thrun table 6.1 with ray-cast expected ranges (amcl "beam")
};

/// Where the beam model's expected ranges come from.
enum class RayCasting : std::uint8_t {
  kExact,  ///< an Embree ray per particle and beam
  kTable,  ///< a precomputed range table (RangeTable), built with the Localizer
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
  int min_particles = 500;  ///< lower bound of the KLD-adaptive count
  /// Upper bound of the KLD-adaptive count and of the initial sets. nav2: 2000, which leaves
  /// global localization of a whole building with a particle every few metres. 500000 is 34 MB
  /// of particles (68 bytes each), held only for the few updates a global start stays that
  /// large: the Wean replay takes 1.4 s instead of 0.9 s.
  int max_particles = 500000;
  /// Global initialization draws this many particles per KLD bin of free space (free area /
  /// kld_bin_xy^2 times the heading bins), within [min_particles, max_particles]: one per bin
  /// puts a particle within half a bin (25 cm, 5 degrees) of any pose, the basin from which the
  /// likelihood field pulls it in; more make it likely that several start near the truth, and
  /// those few must outlive the collapse from the whole building to a few hundred particles in
  /// the first five updates. Measured, Wean global localization (69000 bins), seeds ending
  /// away from the doorway the robot drove to: 2 per bin (capped at 100000) 8 of seeds 1-120;
  /// 2 per bin uncapped 3 of 1-80; 4 per bin 1 of 1-80 and 1 of 1-40 under MOTE_ISA=generic
  /// and avx2 each; 6 per bin none of 1-120, nor of 1-40 under generic and avx2. Above 0,
  /// initialize() also keeps only the shortest prefix of its max_particles Gaussian draws that
  /// Fox's rule finds large enough. 0 draws max_particles at both initializations (nav2).
  double global_particles_per_bin = 6.0;
  double pf_err = 0.05;  ///< KLD epsilon: max K-L divergence between sample and true posterior
  /// KLD confidence. With kld_z_is_quantile false (mote's default) it is the probability 1 - delta
  /// whose standard-normal quantile enters Fox's formula; true reads it as that quantile itself,
  /// as ROS amcl's code does (pf_z 0.99 then means z = 0.99, a far looser bound).
  double pf_z = 0.99;
  bool kld_z_is_quantile = false;
  double kld_bin_xy = 0.5;                    ///< m, KLD histogram bin edge in x and y
  double kld_bin_theta = 0.1745329251994330;  ///< rad (10 degrees), KLD bin edge in heading

  // --- resampling, the localization state and re-localization ------------------------------
  int resample_interval = 1;           ///< filter updates between resampling opportunities
  double resample_ess_fraction = 0.5;  ///< resample only when ESS < fraction * N (1 = always)
  /// The smoothed misfit of the scan at the refined best pose (the share of readings that see
  /// through a mapped obstacle plus the share that end away from any: localization_state.hpp)
  /// above which the filter is lost. Raise it for a map with much glass or many doors drawn
  /// closed; it is at most 2.
  double lost_misfit = 0.6;
  /// Move the lost bound up, by at most a third of lost_misfit, to what this map and laser show
  /// while surely tracking (a control chart, localization_state.hpp): a map with glass or doors
  /// drawn closed then does not read lost wherever the robot sees through it. nav2: off.
  bool lost_misfit_learned = true;
  /// When the filter has been lost for a few updates, add a global set (global_count(), uniform
  /// over free space) that carries half of the belief, the particles it had keeping the other
  /// half: the cost of a global initialization's first update, once, instead of injecting
  /// particles update after update, and a hypothesis that still explains the scans keeps its
  /// weight (relocalize.cpp). Repeated re-localizations wait twice as long each time. nav2: off.
  bool relocalize_when_lost = true;
  /// Augmented MCL as amcl runs it (Thrun table 8.3): w_slow and w_fast average the scan's mean
  /// likelihood, and max(0, 1 - w_fast / w_slow) of the particles are replaced by free-space
  /// poses each update. 0 (mote's and nav2's default) turns it off: mote re-localizes when lost
  /// instead (relocalize_when_lost). Both set: alpha_slow < alpha_fast.
  double recovery_alpha_slow = 0.0;
  double recovery_alpha_fast = 0.0;  ///< w_fast smoothing rate (Thrun suggests 0.1)

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
  /// Fit alpha1..alpha4 online from the filter's corrections (odometry_noise.hpp), starting
  /// from the values above: each leaves them as soon as the upper end of its 95 % confidence
  /// interval is below them, and follows the fit alone after 20 updates (diff model only: omni
  /// and Ackermann read their alphas differently; nav2: off).
  bool adaptive_motion_noise = true;
  /// adaptive_motion_noise: the variance factor on the fitted noise (OdometryNoiseConfig::safety,
  /// which says why 4). `mote calibrate` chooses it per log.
  double motion_noise_margin = 4.0;

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
  /// beams; MRPT's powFactor). 0 (mote's default) chooses tau per update (adaptive tempering,
  /// tempering.hpp); a value in (0, 1] fixes it; 1 is the plain product (nav2).
  double likelihood_tempering = 0.0;
  /// With adaptive tempering (likelihood_tempering 0): the fixed exponent to use instead once
  /// the belief has settled on a few tight hypotheses (the unmapped-obstacle filter's test,
  /// blocked_beams.hpp), e.g. the share of independent beams `mote calibrate` measures from the
  /// beams' correlation. Global localization keeps the adaptive search, which a fixed exponent
  /// near 1 defeats; tracking gets the measurement model's own. 0 (default): adaptive throughout.
  double tracking_tempering = 0.0;
  /// Adaptive tempering: the scan may lower the ESS to this share of its value before the scan.
  double tempering_ess_fraction = 0.1;
  /// Beam model: unknown cells stop rays as walls do (amcl's map_calc_range). Off (mote's
  /// default): an unknown cell is one nobody saw, not an obstacle, as the likelihood field reads
  /// it; a map rendered from log-odds (the dev/ maps) leaves whole rooms grey, and with them
  /// blocking the beam model was lost on edmonton (23 m) and 0.11 m on acapulco, against
  /// 0.083 m and 0.073 m with them open (no flags, docs/localization-state.md). nav2: on.
  bool unknown_cells_block_rays = false;
  /// Beam model: a precomputed range table (range_table.hpp) or exact Embree casting, which
  /// amcl does (nav2_defaults()). With no flags the table tracked every log with reference
  /// poses at exact casting's ATE (within a millimetre), at a third of its median update time
  /// and with the p99 within 10 times the median where exact casting's was 13-18 times
  /// (BENCHMARKS.md, "Range table").
  RayCasting ray_casting = RayCasting::kTable;
  /// Range table: directions over the full circle, a positive multiple of 32.
  int range_table_angles = 512;
  /// Range table: memory budget (MB). When the table on every cell does not fit, it is built on
  /// a coarser lattice (a point every 2, 3, ... cells) of at most sqrt(2) sigma_hit; past that
  /// the beam model casts exactly (BeamModel, BeamCasting).
  double range_table_budget_mb = 256.0;
  /// Once the belief has settled on one place, leave out, for every particle alike, the beams
  /// that most of it finds blocked by something the map does not hold (people, a crowd, furniture):
  /// the reading ends well short of the first mapped wall along the beam (Fox et al. 1999's
  /// distance filter, blocked_beams.hpp). nav2: off (its beam skipping is not implemented).
  bool unmapped_obstacle_filter = true;

  // --- execution -----------------------------------------------------------------------------
  int threads = 0;           ///< worker threads; 0 = every core
  std::uint64_t seed = 42;   ///< random seed; same seed + input = same output
  std::size_t grain = 4096;  ///< particles per parallel task (results never depend on it)

  /// Throws ConfigError naming the first parameter out of its valid range.
  void validate() const;

  friend bool operator==(const LocalizerConfig&, const LocalizerConfig&) = default;
};

/// nav2_amcl's defaults (the values amcl users compare against): 500-2000 particles, the
/// plain product of beams (tempering 1), no recovery, every particle drawn at global
/// initialization. `defaults: nav2` in a config file and `--nav2-defaults` select it.
[[nodiscard]] LocalizerConfig nav2_defaults();

/// Which defaults the keys a configuration file leaves out take.
enum class ConfigDefaults : std::uint8_t {
  kMote,  ///< LocalizerConfig{}: mote's adaptive mechanisms, the file's values where they start
  kNav2,  ///< nav2_defaults(): nav2_amcl's fixed behaviour, formula for formula
};

/// A configuration read from a file, with the warnings it produced and what it started from.
struct LoadedConfig {
  LocalizerConfig config;
  /// Keys asking for what mote does not do (do_beamskip: true, ...), each naming file and line.
  std::vector<std::string> warnings;
  ConfigDefaults defaults = ConfigDefaults::kMote;  ///< the base the file's keys were applied to
  bool nav2_params = false;  ///< a nav2 or ROS amcl params file (an `amcl:` section)
  std::string source;        ///< the file as named in messages; empty for no file
};

/// Reads a LocalizerConfig from YAML: either a flat map of the fields above (amcl names), or a
/// nav2 params file as it is (the `amcl: ros__parameters:` section is used). Keys absent from
/// the file keep mote's defaults, for a nav2 params file too: its values apply over them, the
/// alphas and the sensor mixture as where mote's adaptive mechanisms start (the odometry-noise
/// fit, the adaptive likelihood exponent). `defaults: nav2` in the file, or `defaults` =
/// kNav2 from the caller, applies the keys over nav2_defaults() instead: amcl's behaviour;
/// the file and the caller naming different defaults is an InputError. The node's keys
/// (frames, topics, tf, start pose: node_params.hpp) and ROS plumbing (use_sim_time) pass in
/// silence; so does a key for what mote does not do at the value that turns it off
/// (`do_beamskip: false`), which warns at any other value. An unknown key, a wrong type or an
/// out-of-range value throws InputError naming the file, the line and the key.
[[nodiscard]] LoadedConfig load_config(const std::filesystem::path& yaml,
                                       std::optional<ConfigDefaults> defaults = std::nullopt);

/// As load_config, from YAML text; `name` stands for the file in messages.
[[nodiscard]] LoadedConfig parse_config(const std::string& yaml_text, const std::string& name,
                                        std::optional<ConfigDefaults> defaults = std::nullopt);

/// What a run uses, in the lines it prints first: which defaults, and for a file, how its keys
/// apply ("defaults: mote's adaptive ones ...", "config: FILE, a nav2 params file: ...").
/// Without a file (`loaded.source` empty), the defaults line alone.
[[nodiscard]] std::vector<std::string> config_summary(const LoadedConfig& loaded);

/// The name load_config reads each model by (the first of its spellings).
[[nodiscard]] const char* name_of(LaserModel model);
[[nodiscard]] const char* name_of(OdomModel model);
[[nodiscard]] const char* name_of(LikelihoodCombination combination);
[[nodiscard]] const char* name_of(RayCasting casting);
[[nodiscard]] const char* name_of(ConfigDefaults defaults);  ///< "mote" or "nav2"

/// The flat YAML (one `key: value` line per field, load_config's names) of every field of
/// `config` that differs from `base`, doubles written to round-trip. Against mote's defaults
/// (the default base) parse_config of the text gives `config` back exactly; against
/// nav2_defaults() it does with a `defaults: nav2` line in front. Empty when nothing differs
/// (load_config refuses an empty file).
[[nodiscard]] std::string config_yaml(const LocalizerConfig& config,
                                      const LocalizerConfig& base = {});

}  // namespace mote
