#pragma once
/// \file
/// The case matrix of the end-to-end benchmark: sensor model x particles x beams x threads x
/// setting, named so the results table can be rebuilt from the benchmark names alone.

#include <cstdint>
#include <string>
#include <vector>

#include "mote/engine/localizer_config.hpp"

namespace mote::bench {

/// Where the particles are when an update starts.
enum class Setting : std::uint8_t {
  kTracking,  ///< around the true pose, following the drive update after update
  kGlobal,    ///< uniform over the map's free space (global localization's first update)
};

/// One benchmark case.
struct Case {
  LaserModel model = LaserModel::kLikelihoodField;
  Setting setting = Setting::kTracking;
  int particles = 0;
  int beams = 0;
  int threads = 1;
  /// nav2_defaults() instead of mote's (fixed tempering 1, no recovery, fixed odometry
  /// noise): the baseline the adaptive mechanisms' cost is read against, in the same run.
  bool nav2 = false;
  /// 0: the particle count is fixed at `particles` (KLD cannot change it). Otherwise
  /// KLD-adaptive: min_particles = kld_min, max_particles = particles.
  int kld_min = 0;
  /// Beam model only: where the expected ranges come from (exact Embree casting or the range
  /// table).
  RayCasting ray_casting = RayCasting::kExact;

  /// "BM_Localizer_Update/<model>/<setting>/n:<particles>/beams:<beams>/threads:<threads>",
  /// with "/defaults:nav2" appended for the nav2 baseline and "/kld_min:<kld_min>" for the
  /// KLD-adaptive cases (n is then max_particles) and "/ray_casting:table" for the table.
  [[nodiscard]] std::string name() const;
};

/// Every case (mote's defaults), ordered so that consecutive cases share one filter (same model,
/// particle count and thread count): tracking then global, each over the beam counts.
[[nodiscard]] std::vector<Case> all_cases();

/// The nav2-defaults twins of the tracking cases at 10k and 100k particles, 60 beams,
/// 2 threads, for both models.
[[nodiscard]] std::vector<Case> nav2_baseline_cases();

/// The beam model's tracking cases at 10k and 100k particles, 60 beams, 2 threads, with exact
/// Embree casting and with the range table, side by side (issue 19).
[[nodiscard]] std::vector<Case> range_table_cases();

/// KLD-adaptive twins (min 500, max n) of the headline cases, 60 beams, 2 threads: likelihood
/// field 100k and 1M, beam model 10k, tracking and global.
[[nodiscard]] std::vector<Case> kld_cases();

}  // namespace mote::bench
