#pragma once
/// \file
/// Temp files and whole-log reading for the replay tests.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mote/logs/scan_source.hpp"

namespace mote::test {

/// A fresh directory under the system temp dir, named after the running test.
inline std::filesystem::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      (std::string("mote_replay_") + info->test_suite_name() + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
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
