// The edit distance and the closest-word suggestion behind "did you mean" in flags and keys.
#include "mote/core/did_you_mean.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string_view>

namespace mote {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(edit_distance("", ""), 0U);
  EXPECT_EQ(edit_distance("", "abc"), 3U);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3U);  // the textbook pair
  EXPECT_EQ(edit_distance("particles", "partcles"), 1U);
  EXPECT_EQ(edit_distance("partciles", "particles"), 2U);  // a swap is two edits
  EXPECT_EQ(edit_distance("sigma_hit", "sigma_hit"), 0U);
}

TEST(ClosestWord, SuggestsOnlyWordsATypoAway) {
  constexpr std::array<std::string_view, 4> kKeys{"sigma_hit", "z_hit", "max_particles",
                                                  "min_particles"};
  EXPECT_EQ(closest_word("sigma_hitt", kKeys), "sigma_hit");
  EXPECT_EQ(closest_word("max_partcles", kKeys), "max_particles");
  EXPECT_EQ(closest_word("min_particle", kKeys), "min_particles");
  EXPECT_EQ(closest_word("odom_frame_id", kKeys), "");  // another word, not a typo
  EXPECT_EQ(closest_word("zz", kKeys), "");
}

}  // namespace
}  // namespace mote
