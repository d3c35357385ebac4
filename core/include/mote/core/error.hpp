#pragma once
/// \file
/// The exception types mote throws. Every reader and loader throws InputError with the file, the
/// place (line, byte offset, key) and what was expected (design.md section 3, "Bad input").

#include <stdexcept>
#include <string>
#include <utility>

namespace mote {

/// Base of every exception mote throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Malformed or unreadable input. what() reads "FILE: PLACE: PROBLEM" on one line.
class InputError : public Error {
 public:
  InputError(std::string file, std::string place, const std::string& problem)
      : Error(format(file, place, problem)),
        file_(std::move(file)),
        place_(std::move(place)),
        problem_(problem) {}

  /// The file (or stream name) the input came from.
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  /// Where in it: "line 12", "byte 4096", "key 'resolution'"; may be empty.
  [[nodiscard]] const std::string& place() const noexcept { return place_; }
  /// What is wrong there, without the file and the place (to rethrow it with more said).
  [[nodiscard]] const std::string& problem() const noexcept { return problem_; }

 private:
  static std::string format(const std::string& file, const std::string& place,
                            const std::string& problem) {
    return printable(place.empty() ? file + ": " + problem : file + ": " + place + ": " + problem);
  }
  /// Problems often quote the input, which may hold any byte: control characters are escaped
  /// (\n, \xHH) so the message stays one line.
  static std::string printable(const std::string& text) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (const char c : text) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte >= 0x20 && byte != 0x7f) {
        out += c;
      } else if (c == '\n') {
        out += "\\n";
      } else {
        out += {'\\', 'x', kHex[byte >> 4U], kHex[byte & 0xfU]};
      }
    }
    return out;
  }

  std::string file_;
  std::string place_;
  std::string problem_;
};

/// A configuration value out of its valid range, or an API used against its contract.
class ConfigError : public Error {
 public:
  using Error::Error;
};

}  // namespace mote
