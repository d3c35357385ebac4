// LocalizerConfig with the C++ field names as attributes, LocalizerConfig(**fields), and the
// YAML loader (warnings for unknown keys become Python warnings).
#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bindings.hpp"
#include "mote/core/did_you_mean.hpp"
#include "mote/engine/localizer_config.hpp"

namespace mote::python {
namespace {

// Every field of LocalizerConfig, in header order (kept by hand: one line a field, so
// clang-format is off for it; python/tests/test_api.py checks it against the header).
// clang-format off
#define MOTE_CONFIG_FIELDS(X) \
  X(min_particles) \
  X(max_particles) \
  X(global_particles_per_bin) \
  X(pf_err) \
  X(pf_z) \
  X(kld_z_is_quantile) \
  X(kld_bin_xy) \
  X(kld_bin_theta) \
  X(resample_interval) \
  X(resample_ess_fraction) \
  X(recovery_alpha_slow) \
  X(recovery_alpha_fast) \
  X(lost_misfit) \
  X(lost_misfit_learned) \
  X(relocalize_when_lost) \
  X(update_min_d) \
  X(update_min_a) \
  X(odom_jump_max_d) \
  X(odom_model_type) \
  X(amcl_motion_conventions) \
  X(alpha1) \
  X(alpha2) \
  X(alpha3) \
  X(alpha4) \
  X(alpha5) \
  X(wheelbase) \
  X(adaptive_motion_noise) \
  X(motion_noise_margin) \
  X(laser_model_type) \
  X(likelihood_combination) \
  X(max_beams) \
  X(laser_min_range) \
  X(laser_max_range) \
  X(z_hit) \
  X(z_short) \
  X(z_max) \
  X(z_rand) \
  X(sigma_hit) \
  X(lambda_short) \
  X(laser_likelihood_max_dist) \
  X(likelihood_tempering) \
  X(tempering_ess_fraction) \
  X(tracking_tempering) \
  X(unknown_cells_block_rays) \
  X(ray_casting) \
  X(range_table_angles) \
  X(range_table_budget_mb) \
  X(unmapped_obstacle_filter) \
  X(threads) \
  X(seed) \
  X(grain)
// clang-format on

#define MOTE_FIELD_NAME(name) std::string_view{#name},
constexpr std::array kFieldNames{MOTE_CONFIG_FIELDS(MOTE_FIELD_NAME)};
#undef MOTE_FIELD_NAME

// "LocalizerConfig has no field 'max_particle' (did you mean 'max_particles'?)", as the tool
// says of a misspelled flag or key.
std::string unknown_field(const std::string& name) {
  std::string message = "LocalizerConfig has no field '";
  message.append(name).append("'");
  const std::string near = closest_word(name, kFieldNames);
  if (!near.empty()) message.append(" (did you mean '").append(near).append("'?)");
  return message;
}

LocalizerConfig config_from(const LocalizerConfig& base, const py::kwargs& fields) {
  LocalizerConfig c = base;
  const py::object self = py::cast(&c, py::return_value_policy::reference);
  for (const auto& [key, value] : fields) {
    const auto name = key.cast<std::string>();
    if (name.starts_with("_") || !py::hasattr(self, name.c_str()))
      throw py::type_error(unknown_field(name));
    self.attr(name.c_str()) = value;
  }
  return c;
}

void bind_enums(py::module_& m) {
  py::enum_<LaserModel>(m, "LaserModel", "Which measurement model weighs the particles.")
      .value("LIKELIHOOD_FIELD", LaserModel::kLikelihoodField)
      .value("BEAM", LaserModel::kBeam);
  py::enum_<LikelihoodCombination>(m, "LikelihoodCombination",
                                   "How the likelihood field combines beams.")
      .value("PRODUCT", LikelihoodCombination::kProduct)
      .value("AMCL_CUBED_SUM", LikelihoodCombination::kAmclCubedSum);
  py::enum_<OdomModel>(m, "OdomModel", "Which motion model samples the particles forward.")
      .value("DIFF", OdomModel::kDiff)
      .value("OMNI", OdomModel::kOmni)
      .value("ACKERMANN", OdomModel::kAckermann);
  py::enum_<RayCasting>(m, "RayCasting", "Where the beam model's expected ranges come from.")
      .value("EXACT", RayCasting::kExact)
      .value("TABLE", RayCasting::kTable);
}

std::string config_repr(const LocalizerConfig& c) {
  const py::object self = py::cast(c);
  std::string out = "LocalizerConfig(";
  bool first = true;
#define MOTE_REPR_FIELD(name)                                        \
  out += (first ? "" : ", ");                                        \
  out += #name "=" + py::repr(self.attr(#name)).cast<std::string>(); \
  first = false;
  MOTE_CONFIG_FIELDS(MOTE_REPR_FIELD)
#undef MOTE_REPR_FIELD
  return out + ")";
}

}  // namespace

void bind_config(py::module_& m) {
  bind_enums(m);
  py::class_<LocalizerConfig> cls(
      m, "LocalizerConfig",
      "Every parameter of the Localizer, with the C++ field names (amcl's where they overlap). "
      "Units: m, rad, s. LocalizerConfig(**fields) starts from mote's defaults; see "
      "engine/include/mote/engine/localizer_config.hpp for each field's meaning.");
  cls.def(py::init([](const py::kwargs& fields) { return config_from({}, fields); }))
      .def(
          "replace",
          [](const LocalizerConfig& c, const py::kwargs& fields) { return config_from(c, fields); },
          "A copy with the given fields changed.")
      .def("validate", &LocalizerConfig::validate,
           "Raises ConfigError naming the first parameter out of its valid range.")
      .def("__repr__", &config_repr);
#define MOTE_BIND_FIELD(name) cls.def_readwrite(#name, &LocalizerConfig::name);
  MOTE_CONFIG_FIELDS(MOTE_BIND_FIELD)
#undef MOTE_BIND_FIELD
  cls.def_property_readonly_static("fields", [](const py::object&) {
    py::list names;
#define MOTE_LIST_FIELD(name) names.append(#name);
    MOTE_CONFIG_FIELDS(MOTE_LIST_FIELD)
#undef MOTE_LIST_FIELD
    return names;
  });

  m.def(
      "_closest_word",
      [](const std::string& word, const std::vector<std::string>& candidates) {
        return closest_word(word, candidates);
      },
      py::arg("word"), py::arg("candidates"),
      "The candidate a misspelled word most likely meant, or '' (the tool's did-you-mean rule: "
      "edit distance within a third of the word's length, at least 2).");
  m.def("nav2_defaults", &nav2_defaults, "nav2_amcl's defaults (500-2000 particles, no recovery).");
  m.def(
      "load_config",
      [](const std::string& path) {
        const LoadedConfig loaded = load_config(path);
        const py::object warn = py::module_::import("warnings").attr("warn");
        for (const std::string& w : loaded.warnings) warn(w);
        return loaded.config;
      },
      py::arg("path"),
      "Reads a LocalizerConfig from YAML (flat amcl names or a nav2 params file). Unknown keys "
      "give a warning; a wrong type or out-of-range value raises InputError naming file and key.");
  m.def(
      "config_yaml",
      [](const LocalizerConfig& config, const std::optional<LocalizerConfig>& base) {
        return config_yaml(config, base.value_or(LocalizerConfig{}));
      },
      py::arg("config"), py::arg("base") = py::none(),
      "The flat YAML of every field that differs from base (default: mote's defaults); "
      "against mote's defaults load_config reads it back exactly.");
}

}  // namespace mote::python
