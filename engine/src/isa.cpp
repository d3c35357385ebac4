// How the engine was compiled, beside the variant chosen (isa.hpp; the choice itself is
// mote/core/isa.hpp).
#include "mote/engine/isa.hpp"

#include "mote/core/isa_target.hpp"

namespace mote {

std::string isa_description() {
#if defined(MOTE_NATIVE_BUILD)
  constexpr std::string_view kBuild = "library compiled with -march=native";
#else
  constexpr std::string_view kBuild = "library compiled for the compiler's default target";
#endif
  const std::string_view how = MOTE_ISA_DISPATCH ? "dispatched" : "no dispatch on this target";
  return std::string(isa_name(active_isa())) + " (" + std::string(how) + "; " +
         std::string(kBuild) + ")";
}

}  // namespace mote
