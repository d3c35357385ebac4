// Reads LocalizerConfig from YAML: a flat map of amcl-named keys, or a nav2 params file with its
// `amcl: ros__parameters:` section.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <concepts>
#include <functional>
#include <optional>
#include <string_view>

#include "mote/core/did_you_mean.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/localizer_config.hpp"
#include "params_yaml.hpp"

namespace mote {

namespace {

using detail::place_of;
using detail::warning;
using Setter = std::function<void(LocalizerConfig&, const YAML::Node&)>;
using Getter = std::function<std::string(const LocalizerConfig&)>;

struct Key {
  std::string_view name;
  std::string_view expected;  // for error messages
  Setter set;
  Getter get;  // the value as the setter reads it back; empty for an alias of another key
};

// Shortest text that reads back to the same double (std::to_chars round-trips).
std::string text_of(double v) {
  std::array<char, 32> buf{};
  const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr;
  return {buf.data(), end};
}
std::string text_of(bool v) { return v ? "true" : "false"; }
template <std::integral T>
std::string text_of(T v) {
  return std::to_string(v);
}

template <class T, class Field>
Key field(std::string_view name, std::string_view expected, Field LocalizerConfig::*member) {
  return {name, expected,
          [member](LocalizerConfig& c, const YAML::Node& n) { c.*member = n.as<T>(); },
          [member](const LocalizerConfig& c) { return text_of(static_cast<T>(c.*member)); }};
}

LaserModel parse_laser_model(const std::string& s) {
  // amcl's likelihood_field_prob adds beam skipping on top of the likelihood field.
  if (s == "likelihood_field" || s == "likelihood_field_prob") return LaserModel::kLikelihoodField;
  if (s == "beam") return LaserModel::kBeam;
  throw YAML::BadConversion(YAML::Mark::null_mark());
}

OdomModel parse_odom_model(const std::string& s) {
  if (s == "diff" || s == "diff-corrected" || s == "differential" ||
      s == "nav2_amcl::DifferentialMotionModel") {
    return OdomModel::kDiff;
  }
  if (s == "omni" || s == "omni-corrected" || s == "omnidirectional" ||
      s == "nav2_amcl::OmniMotionModel") {
    return OdomModel::kOmni;
  }
  if (s == "ackermann") return OdomModel::kAckermann;
  throw YAML::BadConversion(YAML::Mark::null_mark());
}

LikelihoodCombination parse_combination(const std::string& s) {
  if (s == "product") return LikelihoodCombination::kProduct;
  if (s == "amcl") return LikelihoodCombination::kAmclCubedSum;
  throw YAML::BadConversion(YAML::Mark::null_mark());
}

template <class Enum>
Key enum_key(std::string_view name, std::string_view expected,
             std::function<void(LocalizerConfig&, const std::string&)> set,
             Enum LocalizerConfig::*member) {
  Getter get;
  if (member != nullptr) get = [member](const LocalizerConfig& c) { return name_of(c.*member); };
  return {name, expected,
          [set = std::move(set)](LocalizerConfig& c, const YAML::Node& n) {
            set(c, n.as<std::string>());
          },
          std::move(get)};
}

const std::vector<Key>& keys() {
  static const std::vector<Key> table = [] {
    constexpr std::string_view kNum = "a number";
    constexpr std::string_view kInt = "an integer";
    constexpr std::string_view kBool = "true or false";
    std::vector<Key> k{
        field<int>("min_particles", kInt, &LocalizerConfig::min_particles),
        field<int>("max_particles", kInt, &LocalizerConfig::max_particles),
        field<double>("pf_err", kNum, &LocalizerConfig::pf_err),
        field<double>("pf_z", kNum, &LocalizerConfig::pf_z),
        field<bool>("kld_z_is_quantile", kBool, &LocalizerConfig::kld_z_is_quantile),
        field<double>("kld_bin_xy", kNum, &LocalizerConfig::kld_bin_xy),
        field<double>("kld_bin_theta", kNum, &LocalizerConfig::kld_bin_theta),
        field<int>("resample_interval", kInt, &LocalizerConfig::resample_interval),
        field<double>("resample_ess_fraction", kNum, &LocalizerConfig::resample_ess_fraction),
        field<double>("recovery_alpha_slow", kNum, &LocalizerConfig::recovery_alpha_slow),
        field<double>("recovery_alpha_fast", kNum, &LocalizerConfig::recovery_alpha_fast),
        field<double>("update_min_d", kNum, &LocalizerConfig::update_min_d),
        field<double>("update_min_a", kNum, &LocalizerConfig::update_min_a),
        field<double>("odom_jump_max_d", kNum, &LocalizerConfig::odom_jump_max_d),
        field<bool>("amcl_motion_conventions", kBool, &LocalizerConfig::amcl_motion_conventions),
        field<double>("alpha1", kNum, &LocalizerConfig::alpha1),
        field<double>("alpha2", kNum, &LocalizerConfig::alpha2),
        field<double>("alpha3", kNum, &LocalizerConfig::alpha3),
        field<double>("alpha4", kNum, &LocalizerConfig::alpha4),
        field<double>("alpha5", kNum, &LocalizerConfig::alpha5),
        field<double>("wheelbase", kNum, &LocalizerConfig::wheelbase),
        field<bool>("adaptive_motion_noise", kBool, &LocalizerConfig::adaptive_motion_noise),
        field<double>("motion_noise_margin", kNum, &LocalizerConfig::motion_noise_margin),
        field<bool>("unmapped_obstacle_filter", kBool, &LocalizerConfig::unmapped_obstacle_filter),
        field<int>("max_beams", kInt, &LocalizerConfig::max_beams),
        field<double>("laser_min_range", kNum, &LocalizerConfig::laser_min_range),
        field<double>("laser_max_range", kNum, &LocalizerConfig::laser_max_range),
        field<double>("z_hit", kNum, &LocalizerConfig::z_hit),
        field<double>("z_short", kNum, &LocalizerConfig::z_short),
        field<double>("z_max", kNum, &LocalizerConfig::z_max),
        field<double>("z_rand", kNum, &LocalizerConfig::z_rand),
        field<double>("sigma_hit", kNum, &LocalizerConfig::sigma_hit),
        field<double>("lambda_short", kNum, &LocalizerConfig::lambda_short),
        field<double>("laser_likelihood_max_dist", kNum,
                      &LocalizerConfig::laser_likelihood_max_dist),
        {"likelihood_tempering", "a number or auto",
         [](LocalizerConfig& c, const YAML::Node& n) {
           c.likelihood_tempering = n.as<std::string>() == "auto" ? 0.0 : n.as<double>();
         },
         [](const LocalizerConfig& c) { return text_of(c.likelihood_tempering); }},
        field<double>("tempering_ess_fraction", kNum, &LocalizerConfig::tempering_ess_fraction),
        field<double>("tracking_tempering", kNum, &LocalizerConfig::tracking_tempering),
        field<double>("global_particles_per_bin", kNum, &LocalizerConfig::global_particles_per_bin),
        field<double>("lost_misfit", kNum, &LocalizerConfig::lost_misfit),
        field<bool>("lost_misfit_learned", kBool, &LocalizerConfig::lost_misfit_learned),
        field<bool>("relocalize_when_lost", kBool, &LocalizerConfig::relocalize_when_lost),
        field<bool>("unknown_cells_block_rays", kBool, &LocalizerConfig::unknown_cells_block_rays),
        enum_key(
            "ray_casting", "exact or table",
            [](LocalizerConfig& c, const std::string& s) {
              if (s == "exact")
                c.ray_casting = RayCasting::kExact;
              else if (s == "table")
                c.ray_casting = RayCasting::kTable;
              else
                throw YAML::BadConversion(YAML::Mark::null_mark());
            },
            &LocalizerConfig::ray_casting),
        field<int>("range_table_angles", kInt, &LocalizerConfig::range_table_angles),
        field<double>("range_table_budget_mb", kNum, &LocalizerConfig::range_table_budget_mb),
        field<int>("threads", kInt, &LocalizerConfig::threads),
        field<std::uint64_t>("seed", kInt, &LocalizerConfig::seed),
        field<std::size_t>("grain", kInt, &LocalizerConfig::grain),
        enum_key(
            "laser_model_type", "likelihood_field, likelihood_field_prob or beam",
            [](LocalizerConfig& c, const std::string& s) {
              c.laser_model_type = parse_laser_model(s);
            },
            &LocalizerConfig::laser_model_type),
        enum_key(
            "odom_model_type", "diff, omni, diff-corrected, omni-corrected or ackermann",
            [](LocalizerConfig& c, const std::string& s) {
              c.odom_model_type = parse_odom_model(s);
            },
            &LocalizerConfig::odom_model_type),
        enum_key(
            "robot_model_type", "nav2_amcl::DifferentialMotionModel or nav2_amcl::OmniMotionModel",
            [](LocalizerConfig& c, const std::string& s) {
              c.odom_model_type = parse_odom_model(s);
            },
            static_cast<OdomModel LocalizerConfig::*>(nullptr)),  // odom_model_type's alias
        enum_key(
            "likelihood_combination", "product or amcl",
            [](LocalizerConfig& c, const std::string& s) {
              c.likelihood_combination = parse_combination(s);
            },
            &LocalizerConfig::likelihood_combination),
        {"selective_resampling", kBool,
         [](LocalizerConfig& c, const YAML::Node& n) {
           // amcl's selective resampling is the N/2 effective-sample-size rule; off = always.
           c.resample_ess_fraction = n.as<bool>() ? 0.5 : 1.0;
         },
         Getter{}},  // an alias of resample_ess_fraction
        {"random_seed", kInt,
         [](LocalizerConfig& c, const YAML::Node& n) {
           // nav2_amcl: a seed >= 0, or -1 (its default) for one from the clock. mote is
           // deterministic: -1 keeps its seed.
           const auto seed = n.as<std::int64_t>();
           if (seed >= 0) c.seed = static_cast<std::uint64_t>(seed);
         },
         Getter{}},  // an alias of seed
    };
    return k;
  }();
  return table;
}

// ROS plumbing that has no meaning for the filter, accepted without a word. The node's own keys
// (frames, topics, tf, the start pose) are read_node_params's (node_params.hpp).
constexpr std::array<std::string_view, 7> kRosOnlyKeys{
    "use_sim_time",     "bond_heartbeat_period",         "use_map_topic", "gui_publish_rate",
    "restore_defaults", "allow_parameter_qos_overrides", "qos_overrides"};

bool is_ros_only(std::string_view key) {
  return std::ranges::find(kRosOnlyKeys, key) != kRosOnlyKeys.end() || detail::is_node_param(key);
}

constexpr std::string_view kBeamSkipping =
    "beam skipping is not implemented (unmapped_obstacle_filter does its job)";

/// nav2_amcl's keys for what mote does not do. The value nav2 ships, which turns the feature
/// off, asks for nothing and passes in silence; any other value gets the warning.
struct Unsupported {
  std::string_view name;
  std::string_view off;       // the value that asks for nothing
  std::string_view expected;  // for error messages
  std::string_view what;      // the warning's text; empty: any number passes
};

// beam_skip_* only tune what do_beamskip turns on: that key's warning covers them.
constexpr std::array<Unsupported, 7> kUnsupported{{
    {"do_beamskip", "false", "true or false", kBeamSkipping},
    {"beam_skip_distance", "", "a number", ""},
    {"beam_skip_threshold", "", "a number", ""},
    {"beam_skip_error_threshold", "", "a number", ""},
    {"freespace_downsampling", "false", "true or false",
     "mote draws its global set per KLD bin of free space (global_particles_per_bin), not per "
     "cell"},
    {"introspection_mode", "disabled", "disabled, metadata or contents",
     "mote offers no ROS service to introspect"},
    {"service_introspection_mode", "disabled", "disabled, metadata or contents",
     "mote offers no ROS service to introspect"},
}};

/// True when `key` is one of kUnsupported; adds its warning when the value asks for something.
bool check_unsupported(const std::string& key, const YAML::Node& value, const std::string& name,
                       std::vector<std::string>& warnings) {
  const auto u = std::ranges::find(kUnsupported, key, &Unsupported::name);
  if (u == kUnsupported.end()) return false;
  const bool is_bool = u->expected == "true or false";
  bool asks = false;
  try {
    if (is_bool)
      asks = value.as<bool>() != (u->off == "true");
    else if (u->what.empty())
      (void)value.as<double>();
    else
      asks = value.as<std::string>() != u->off;
  } catch (const YAML::Exception&) {
    throw InputError(name, place_of(value, key), "expected " + std::string(u->expected));
  }
  if (asks)
    warnings.push_back(warning(name, place_of(value, key), std::string(u->what) + "; key ignored"));
  return true;
}

void apply_key(LocalizerConfig& config, const std::string& key, const YAML::Node& value,
               const std::string& name, std::vector<std::string>& warnings) {
  for (const Key& k : keys()) {
    if (k.name != key) continue;
    try {
      k.set(config, value);
    } catch (const YAML::Exception&) {
      throw InputError(name, place_of(value, key), "expected " + std::string(k.expected));
    }
    if (key == "laser_model_type" && value.as<std::string>() == "likelihood_field_prob") {
      warnings.push_back(warning(name, place_of(value, key),
                                 std::string(kBeamSkipping) + "; using likelihood_field"));
    }
    return;
  }
  if (check_unsupported(key, value, name, warnings) || is_ros_only(key)) return;
  // A typo must not run on with the default: the run would answer another question.
  std::vector<std::string_view> known;
  for (const Key& k : keys()) known.emplace_back(k.name);
  const std::string best = closest_word(key, known);
  throw InputError(name, place_of(value, key),
                   best.empty() ? "unknown key (the keys are in README, Configuration)"
                                : "unknown key (did you mean '" + best + "'?)");
}

/// "line N, key 'k'" for a key of the file, "key 'k'" for one left at its default.
std::string place_in(const YAML::Node& params, const std::string& key) {
  for (const auto& entry : params) {
    if (entry.first.Scalar() == key) return place_of(entry.second, key);
  }
  return "key '" + key + "'";
}

/// validate(), with its ConfigError ("LocalizerConfig.FIELD: expected ...") placed in the file.
void validate(const LocalizerConfig& c, const YAML::Node& params, const std::string& name) {
  try {
    c.validate();
  } catch (const ConfigError& e) {
    const std::string_view what = e.what();
    constexpr std::string_view kPrefix = "LocalizerConfig.";
    const std::size_t colon = what.find(':');
    const std::string field = what.starts_with(kPrefix) && colon != std::string_view::npos
                                  ? std::string(what.substr(kPrefix.size(), colon - kPrefix.size()))
                                  : std::string();
    throw InputError(name, field.empty() ? "line 1" : place_in(params, field), e.what());
  }
}

/// The defaults the file names (`defaults: mote` or `nav2`), if it names one.
std::optional<ConfigDefaults> named_defaults(const YAML::Node& params, const std::string& name) {
  const YAML::Node choice = params["defaults"];
  if (!choice) return std::nullopt;
  const std::string value = choice.IsScalar() ? choice.Scalar() : std::string();
  if (value == "nav2") return ConfigDefaults::kNav2;
  if (value == "mote") return ConfigDefaults::kMote;
  throw InputError(name, place_of(choice, "defaults"), "expected mote or nav2");
}

// What keys absent from the file default to: mote's, unless the file (`defaults: nav2`) or the
// caller (--nav2-defaults) asks for nav2_amcl's. A nav2 params file starts from mote's too: it
// describes the robot (frames, laser, motion model, particle bounds) more than it chooses amcl's
// algorithm, and under amcl's fixed behaviour every shared log ended lost (issue 46).
ConfigDefaults chosen_defaults(const YAML::Node& params, const std::string& name,
                               std::optional<ConfigDefaults> asked) {
  const std::optional<ConfigDefaults> named = named_defaults(params, name);
  if (asked && named && *asked != *named) {
    throw InputError(name, place_of(params["defaults"], "defaults"),
                     std::string("the file asks for ") + name_of(*named) +
                         "'s defaults, the caller for " + name_of(*asked) + "'s: keep one");
  }
  return asked.value_or(named.value_or(ConfigDefaults::kMote));
}

}  // namespace

LoadedConfig parse_config(const std::string& yaml_text, const std::string& name,
                          std::optional<ConfigDefaults> defaults) {
  const YAML::Node root = detail::parse_params_yaml(yaml_text, name);
  const YAML::Node params = detail::parameter_map(root, name);
  const ConfigDefaults chosen = chosen_defaults(params, name, defaults);
  LoadedConfig loaded{
      .config = chosen == ConfigDefaults::kNav2 ? nav2_defaults() : LocalizerConfig{},
      .warnings = {},
      .defaults = chosen,
      .nav2_params = detail::is_ros_params(root),
      .source = name};
  for (const auto& entry : params) {
    if (entry.first.IsScalar() && entry.first.Scalar() == "defaults") continue;
    apply_key(loaded.config, detail::key_name(entry.first, name), entry.second, name,
              loaded.warnings);
  }
  validate(loaded.config, params, name);
  return loaded;
}

std::string config_yaml(const LocalizerConfig& config, const LocalizerConfig& base) {
  std::string yaml;
  for (const Key& k : keys()) {
    if (!k.get) continue;
    const std::string value = k.get(config);
    if (value != k.get(base)) yaml += std::string(k.name) + ": " + value + "\n";
  }
  return yaml;
}

LoadedConfig load_config(const std::filesystem::path& yaml,
                         std::optional<ConfigDefaults> defaults) {
  return parse_config(detail::read_params_text(yaml), yaml.string(), defaults);
}

}  // namespace mote
