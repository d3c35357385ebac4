#pragma once
// A small command-line parser for the mote tool: `--name value`, `--name=value` and switches,
// checked against a table of flags that also produces the --help text.

#include <cstdint>
#include <iosfwd>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "mote/core/pose.hpp"

namespace mote::tool {

/// Bad usage (unknown flag, missing value, bad number): exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One flag: its name without dashes, the value's placeholder (empty for a switch) and help text
/// with units and default.
struct FlagSpec {
  std::string_view name;
  std::string_view value;
  std::string_view help;
};

/// The flags given on a command line.
class ParsedArgs {
 public:
  ParsedArgs(std::string command, std::map<std::string, std::string> values)
      : command_(std::move(command)), values_(std::move(values)) {}

  [[nodiscard]] bool has(std::string_view name) const;
  /// The value of a flag, or nullopt when absent.
  [[nodiscard]] std::optional<std::string> text(std::string_view name) const;
  /// The value of a required flag; UsageError when absent.
  [[nodiscard]] std::string required(std::string_view name) const;
  /// An integer in [lo, hi]; UsageError when malformed or out of range.
  [[nodiscard]] std::optional<std::int64_t> integer(std::string_view name, std::int64_t lo,
                                                    std::int64_t hi) const;
  /// A finite real number in [lo, hi].
  [[nodiscard]] std::optional<double> real(std::string_view name, double lo, double hi) const;
  /// A UsageError naming the command and a flag.
  [[nodiscard]] UsageError error(std::string_view name, std::string_view problem) const;

 private:
  std::string command_;
  std::map<std::string, std::string> values_;
};

/// Parses `args` (the words after the command name). "--help" is a switch every command has.
[[nodiscard]] ParsedArgs parse_args(std::string_view command, std::span<char* const> args,
                                    std::span<const FlagSpec> specs);

/// Parses a finite real number (the whole text); nullopt when malformed.
[[nodiscard]] std::optional<double> parse_real(std::string_view text);

/// A pose flag "X,Y,THETA" (m, m, rad; theta wrapped); nullopt when absent, UsageError when
/// malformed.
[[nodiscard]] std::optional<Pose2> pose_flag(const ParsedArgs& args, std::string_view name);

/// Prints "usage" and one line per flag.
void print_help(std::ostream& out, std::string_view usage, std::string_view about,
                std::span<const FlagSpec> specs);

}  // namespace mote::tool
