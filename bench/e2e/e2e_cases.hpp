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

  /// "BM_Localizer_Update/<model>/<setting>/n:<particles>/beams:<beams>/threads:<threads>".
  [[nodiscard]] std::string name() const;
};

/// Every case, ordered so that consecutive cases share one filter (same model, particle count
/// and thread count): tracking then global, each over the beam counts.
[[nodiscard]] std::vector<Case> all_cases();

}  // namespace mote::bench
