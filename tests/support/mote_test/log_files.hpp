#pragma once
/// \file
/// Temp folders and whole-log reading for the tests of mote::logs and the layers over it.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "mote/logs/scan_source.hpp"

namespace mote::test {

/// A fresh directory under the system temp dir, named after the running test and this process
/// (ctest runs tests in parallel, and other builds of mote on the machine run the same tests);
/// removed when the process ends.
inline std::filesystem::path temp_dir() {
  struct Folders {
    std::vector<std::filesystem::path> made;
    ~Folders() {
      std::error_code ignored;
      for (const std::filesystem::path& dir : made) std::filesystem::remove_all(dir, ignored);
    }
  };
  static Folders folders;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mote_test_" + std::to_string(getpid()) + "_" +
                                                info->test_suite_name() + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  folders.made.push_back(dir);
  return dir;
}

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Every frame of a log.
inline std::vector<logs::ScanFrame> read_all(logs::ScanSource& source) {
  std::vector<logs::ScanFrame> frames;
  while (auto f = source.next()) frames.push_back(std::move(*f));
  return frames;
}

}  // namespace mote::test
