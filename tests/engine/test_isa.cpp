// The kernel variant (isa.hpp): MOTE_ISA lowers it, never raises it above what the CPU runs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <string_view>

#include "mote/engine/isa.hpp"

namespace mote {
namespace {

TEST(Isa, NamesRoundTrip) {
  EXPECT_EQ(isa_name(Isa::kGeneric), "generic");
  EXPECT_EQ(isa_name(Isa::kAvx2), "avx2");
  EXPECT_EQ(isa_name(Isa::kAvx512), "avx512");
}

// .ci/engine-tests runs this executable with MOTE_ISA set to each variant the CPU has.
TEST(Isa, ActiveIsTheRequestClampedToTheCpu) {
  const Isa best = best_supported_isa();
  const char* env = std::getenv("MOTE_ISA");
  Isa expected = best;
  if (env != nullptr) {
    for (const Isa isa : {Isa::kGeneric, Isa::kAvx2, Isa::kAvx512}) {
      if (std::string_view(env) == isa_name(isa) &&
          static_cast<int>(isa) < static_cast<int>(best)) {
        expected = isa;
      }
    }
  }
  EXPECT_EQ(active_isa(), expected)
      << "MOTE_ISA=" << (env != nullptr ? env : "(unset)") << ", best " << isa_name(best);
  EXPECT_EQ(active_isa(), active_isa());  // chosen once
}

TEST(Isa, DescriptionNamesTheActiveVariant) {
  const std::string d = isa_description();
  EXPECT_EQ(d.rfind(std::string(isa_name(active_isa())), 0), 0U) << d;
}

}  // namespace
}  // namespace mote
