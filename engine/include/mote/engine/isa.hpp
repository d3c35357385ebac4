#pragma once
/// \file
/// The instruction set of mote's dispatched kernels: Isa, isa_name, best_supported_isa and
/// active_isa (mote/core/isa.hpp, shared with the ray casters), and how the engine was compiled.

#include <string>

#include "mote/core/isa.hpp"

namespace mote {

/// One line for `mote --version` and report.json: the active variant and how the library was
/// compiled, e.g. "avx2 (dispatched; library compiled for baseline x86-64)".
[[nodiscard]] std::string isa_description();

}  // namespace mote
