#pragma once
// The filter's config of a run, as `mote replay` and `mote node` read it: the --config file
// (flat, or a nav2 params file) over mote's defaults, or nav2's with --nav2-defaults.

#include "args.hpp"
#include "mote/engine/localizer_config.hpp"

namespace mote::tool {

/// The config the flags ask for; prints the file's warnings as "mote COMMAND: warning: ...".
[[nodiscard]] LoadedConfig run_config(const ParsedArgs& args, const char* command);

}  // namespace mote::tool
