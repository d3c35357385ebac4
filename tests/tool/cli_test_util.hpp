#pragma once
// What the mote tool's tests share: running the executable, reading its outputs.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mote_cli_test {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A folder of this process's own: ctest runs each test in its own process, in parallel.
inline fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("mote_test_cli_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs `mote ARGS` through the shell, stdout captured by popen and stderr through a file.
inline Outcome mote(const std::string& args) {
  const fs::path err = scratch("stderr") / "err.txt";
  const std::string cmd = std::string("'") + MOTE_EXE + "' " + args + " 2>'" + err.string() + "'";
  Outcome o;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return o;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe) != nullptr) o.out += buf.data();
  const int raw = pclose(pipe);
  o.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  o.err = slurp(err);
  return o;
}

// The number after "key": in a report.json; NaN when absent or null.
inline double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + key.size() + 4, nullptr);
}

inline int lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// The last non-empty line of text.
inline std::string last_line(const std::string& text) {
  const std::size_t end = text.find_last_not_of('\n');
  if (end == std::string::npos) return "";
  const std::size_t start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1, end - start);
}

// Every pair of end positions within `bound` metres.
inline void expect_within(const std::vector<std::array<double, 2>>& ends, double bound) {
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (std::size_t j = i + 1; j < ends.size(); ++j) {
      EXPECT_LT(std::hypot(ends[i][0] - ends[j][0], ends[i][1] - ends[j][1]), bound)
          << "seeds " << i + 1 << " and " << j + 1 << " end at (" << ends[i][0] << ", "
          << ends[i][1] << ") and (" << ends[j][0] << ", " << ends[j][1] << ")";
    }
  }
}

// The x, y of the last pose of out_dir/trajectory.tum.
inline std::array<double, 2> end_position(const fs::path& out_dir) {
  std::istringstream last(last_line(slurp(out_dir / "trajectory.tum")));
  double stamp = 0.0;
  std::array<double, 2> xy{std::nan(""), std::nan("")};
  last >> stamp >> xy[0] >> xy[1];
  return xy;
}

}  // namespace mote_cli_test
