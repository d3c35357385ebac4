#include "mote/core/error.hpp"

#include <gtest/gtest.h>

namespace mote {
namespace {

TEST(InputError, NamesFilePlaceAndProblem) {
  const InputError e("maps/a.yaml", "line 3", "expected a number for 'resolution'");
  EXPECT_STREQ(e.what(), "maps/a.yaml: line 3: expected a number for 'resolution'");
  EXPECT_EQ(e.file(), "maps/a.yaml");
  EXPECT_EQ(e.place(), "line 3");
}

TEST(InputError, OmitsAnEmptyPlace) {
  const InputError e("log.clf", "", "cannot open");
  EXPECT_STREQ(e.what(), "log.clf: cannot open");
}

TEST(InputError, IsAMoteError) { EXPECT_THROW(throw InputError("f", "", "p"), Error); }

}  // namespace
}  // namespace mote
