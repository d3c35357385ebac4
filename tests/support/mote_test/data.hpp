#pragma once
/// \file
/// Access to ../shared/data for tests: the recorded logs and maps are not part of the project,
/// so a test that needs one skips with a message when it is absent (design.md section 6).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace mote::test {

/// The data folder: $MOTE_DATA_DIR, else the path configured at build time.
inline std::filesystem::path data_dir() {
  if (const char* env = std::getenv("MOTE_DATA_DIR"); env != nullptr && *env != '\0') return env;
  return MOTE_TEST_DATA_DIR;
}

/// The project's own test inputs (tests/data).
inline std::filesystem::path project_test_data() { return MOTE_TEST_PROJECT_DATA_DIR; }

}  // namespace mote::test

/// Declares `var` as data_dir()/rel and skips the test when that file is absent.
#define MOTE_REQUIRE_DATA(var, rel)                                                    \
  const ::std::filesystem::path var = ::mote::test::data_dir() / (rel);                \
  if (!::std::filesystem::exists(var)) {                                               \
    GTEST_SKIP() << "recorded data not found: " << var.string()                        \
                 << " (set MOTE_DATA_DIR to the shared data folder to run this test)"; \
  }
