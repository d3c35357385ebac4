#include "run_config.hpp"

#include <iostream>

namespace mote::tool {

LoadedConfig run_config(const ParsedArgs& args, const char* command) {
  const std::optional<ConfigDefaults> asked =
      args.has("nav2-defaults") ? std::optional(ConfigDefaults::kNav2) : std::nullopt;
  const auto path = args.text("config");
  if (!path) {
    return {.config = asked ? nav2_defaults() : LocalizerConfig{},
            .warnings = {},
            .defaults = asked.value_or(ConfigDefaults::kMote),
            .nav2_params = false,
            .source = {}};
  }
  LoadedConfig loaded = load_config(*path, asked);
  for (const std::string& w : loaded.warnings)
    std::cerr << "mote " << command << ": warning: " << w << '\n';
  return loaded;
}

}  // namespace mote::tool
