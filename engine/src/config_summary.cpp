// The names the config files read the enums by, and the lines a run prints first about its
// configuration: which defaults, and how a file applies.
#include <string>
#include <vector>

#include "mote/engine/localizer_config.hpp"

namespace mote {

const char* name_of(LaserModel m) { return m == LaserModel::kBeam ? "beam" : "likelihood_field"; }

const char* name_of(OdomModel m) {
  switch (m) {
    case OdomModel::kOmni:
      return "omni";
    case OdomModel::kAckermann:
      return "ackermann";
    case OdomModel::kDiff:
      break;
  }
  return "diff";
}

const char* name_of(LikelihoodCombination m) {
  return m == LikelihoodCombination::kAmclCubedSum ? "amcl" : "product";
}

const char* name_of(RayCasting m) {
  switch (m) {
    case RayCasting::kTable:
      return "table";
    case RayCasting::kExact:
      break;
  }
  return "exact";
}

const char* name_of(ConfigDefaults d) { return d == ConfigDefaults::kNav2 ? "nav2" : "mote"; }

namespace {

std::string defaults_line(const LoadedConfig& loaded) {
  if (loaded.defaults == ConfigDefaults::kNav2) {
    return "defaults: nav2_amcl's fixed behaviour (likelihood exponent 1, fixed odometry noise, "
           "amcl's formulas, no re-localization)";
  }
  std::string line =
      "defaults: mote's adaptive ones (the likelihood exponent, the odometry noise and "
      "re-localization adapt to the log); ";
  line +=
      loaded.source.empty() ? "--nav2-defaults" : "'defaults: nav2' in the file or --nav2-defaults";
  return line + " for nav2_amcl's fixed behaviour";
}

std::string file_line(const LoadedConfig& loaded) {
  std::string line = "config: " + loaded.source;
  if (!loaded.nav2_params) return line + ", its keys over those defaults";
  if (loaded.defaults == ConfigDefaults::kNav2) {
    return line + ", a nav2 params file over nav2_amcl's defaults: every value as amcl reads it";
  }
  return line +
         ", a nav2 params file: its laser, robot model, particle bounds and update thresholds "
         "apply as written; its alphas are where the odometry-noise fit starts (differential "
         "model) and its sensor mixture is weighed by the adaptive likelihood exponent";
}

}  // namespace

std::vector<std::string> config_summary(const LoadedConfig& loaded) {
  std::vector<std::string> lines{defaults_line(loaded)};
  if (!loaded.source.empty()) lines.push_back(file_line(loaded));
  return lines;
}

}  // namespace mote
