#pragma once
/// \file
/// What every mote fuzz target checks besides memory safety: bad input may only end in a
/// mote::Error, and an InputError must name the input and a place on one line (design.md
/// section 3, "Bad input"). Any other outcome aborts, which libFuzzer reports as a finding.

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "mote/core/error.hpp"

namespace mote::fuzz {

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "mote fuzz finding: %s\n", what.c_str());
  std::abort();
}

/// Runs `read`; returns normally when it succeeds or throws a well-formed mote error.
template <class Read>
void expect_clean(const std::string& name, Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    const std::string_view what = e.what();
    if (e.file() != name) finding("InputError names '" + e.file() + "', not '" + name + "'");
    if (e.place().empty()) finding("InputError without a place: " + std::string(what));
    for (const char c : what) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
        finding("InputError message is not one printable line: " + std::string(what));
      }
    }
  } catch (const Error&) {
    // ConfigError and plain mote::Error are allowed: they are mote's own, with a message.
  } catch (const std::exception& e) {
    finding(std::string("exception that is not a mote::Error: ") + e.what());
  } catch (...) {
    finding("exception that is not a std::exception");
  }
}

/// A file of this process's own holding `size` bytes, for readers that take a path. The folder
/// is per process so parallel fuzzing jobs (-jobs=N) never share it.
inline std::filesystem::path write_input(const char* name, const unsigned char* data,
                                         std::size_t size) {
  /// Created on first use, removed when the fuzzer exits normally.
  struct Folder {
    std::filesystem::path path;
    Folder() {
      const std::filesystem::path shm = "/dev/shm";
      const std::filesystem::path base =
          std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
      path = base / ("mote_fuzz_" + std::to_string(getpid()));
      std::filesystem::create_directories(path);
    }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  const std::filesystem::path path = folder.path / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) finding("cannot write the fuzz input to " + path.string());
  return path;
}

}  // namespace mote::fuzz
