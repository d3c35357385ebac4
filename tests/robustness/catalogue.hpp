#pragma once
/// \file
/// The bad-input catalogue's machinery: a case is a file's bytes and what a reader must do with
/// them. Every case must end, quickly, either in an accepted file (where that is allowed) or in
/// mote::InputError naming the file and a place on one line; any other exception, a crash, a
/// hang or a leak (under ASan) fails.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mote/core/error.hpp"

namespace mote::robustness {

namespace fs = std::filesystem;

/// What a reader must do with a case.
enum class Expect : std::uint8_t {
  kError,         ///< throw InputError
  kErrorOrValid,  ///< throw InputError or read the file (a cut at a line end, a harmless flip)
};

struct Case {
  std::string name;
  std::string bytes;
  Expect expect = Expect::kError;
};

/// The longest a reader may take on one case: they are small files, so anything slower is a hang
/// (generous for sanitizer builds on a shared machine).
inline constexpr double kMaxSecondsPerCase = 5.0;

/// A folder of this process's own (ctest runs test processes in parallel), removed when the
/// process ends.
inline fs::path scratch(const std::string& name) {
  struct Folders {
    std::vector<fs::path> made;
    ~Folders() {
      std::error_code ignored;
      for (const fs::path& dir : made) fs::remove_all(dir, ignored);
    }
  };
  static Folders folders;
  const fs::path dir =
      fs::temp_directory_path() / ("mote_robustness_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  folders.made.push_back(dir);
  return dir;
}

inline void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Every prefix of `valid` shorter than it, or `count` of them spread over it when count > 0;
/// `expect(cut)` says what a cut after `cut` bytes must give.
inline std::vector<Case> truncations(const std::string& label, const std::string& valid,
                                     const std::function<Expect(std::size_t)>& expect,
                                     std::size_t count = 0) {
  std::vector<Case> cases;
  const std::size_t n = count == 0 ? valid.size() : count;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t cut = count == 0 ? k : (valid.size() * (k + 1)) / (count + 1) + k % 7;
    if (cut >= valid.size()) continue;
    cases.push_back(
        {label + " cut at byte " + std::to_string(cut), valid.substr(0, cut), expect(cut)});
  }
  return cases;
}

/// `count` copies of `valid` with `flips` random bytes replaced each (fixed seed).
inline std::vector<Case> byte_flips(const std::string& label, const std::string& valid, int count,
                                    int flips, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Case> cases;
  for (int k = 0; k < count; ++k) {
    std::string bad = valid;
    for (int f = 0; f < flips; ++f) bad[rng() % bad.size()] = static_cast<char>(rng() & 0xFFU);
    cases.push_back({label + " flip #" + std::to_string(k), bad, Expect::kErrorOrValid});
  }
  return cases;
}

/// `size` random bytes (fixed seed).
inline std::string random_bytes(std::size_t size, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xFFU);
  return bytes;
}

/// True when `text` is one line of printable characters.
inline bool one_printable_line(const std::string& text) {
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
  }
  return true;
}

/// How a case ended.
struct Outcome {
  bool threw = false;
  std::string message;
};

/// Checks an InputError against the contract: it names `file`, a place, on one line.
inline void check_error(const InputError& e, const std::string& file, const std::string& label) {
  EXPECT_EQ(e.file(), file) << label << ": " << e.what();
  EXPECT_FALSE(e.place().empty()) << label << ": no place in: " << e.what();
  EXPECT_EQ(std::string(e.what()).rfind(file + ": ", 0), 0U) << label << ": " << e.what();
  EXPECT_TRUE(one_printable_line(e.what())) << label << ": " << e.what();
}

/// Writes the case to `file`, runs `read(file)` and checks the outcome against the contract.
inline Outcome run_case(const Case& c, const fs::path& file,
                        const std::function<void(const fs::path&)>& read) {
  write_file(file, c.bytes);
  Outcome out;
  const auto start = std::chrono::steady_clock::now();
  try {
    read(file);
  } catch (const InputError& e) {
    out.threw = true;
    out.message = e.what();
    check_error(e, file.string(), c.name);
  } catch (const std::exception& e) {
    out.threw = true;
    ADD_FAILURE() << c.name << ": an exception that is not InputError: " << e.what();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, kMaxSecondsPerCase) << c.name;
  if (c.expect == Expect::kError) {
    EXPECT_TRUE(out.threw) << c.name << ": accepted";
  }
  return out;
}

/// Runs every case; returns how many threw (a table whose cases all pass proves little).
inline int run_cases(const std::vector<Case>& cases, const fs::path& file,
                     const std::function<void(const fs::path&)>& read) {
  int errors = 0;
  for (const Case& c : cases) errors += run_case(c, file, read).threw ? 1 : 0;
  return errors;
}

}  // namespace mote::robustness
