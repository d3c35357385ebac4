// The tool's flag parser and help printer.
#include "args.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <string>
#include <vector>

#include "mote/core/did_you_mean.hpp"

namespace mote::tool {
namespace {

const FlagSpec* find_spec(std::span<const FlagSpec> specs, std::string_view name) {
  const auto it =
      std::find_if(specs.begin(), specs.end(), [&](const FlagSpec& s) { return s.name == name; });
  return it == specs.end() ? nullptr : &*it;
}

// " (did you mean '--particles'?)" for a flag a typo away from a known one, else "".
std::string suggest(std::span<const FlagSpec> specs, std::string_view name) {
  std::vector<std::string_view> names;
  for (const FlagSpec& s : specs) names.push_back(s.name);
  const std::string best = closest_word(name, names);
  return best.empty() ? "" : " (did you mean '--" + best + "'?)";
}

UsageError usage(std::string_view command, const std::string& problem) {
  return UsageError("mote " + std::string(command) + ": " + problem + " (see mote " +
                    std::string(command) + " --help)");
}

}  // namespace

bool ParsedArgs::has(std::string_view name) const { return values_.contains(std::string(name)); }

std::optional<std::string> ParsedArgs::text(std::string_view name) const {
  const auto it = values_.find(std::string(name));
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string ParsedArgs::required(std::string_view name) const {
  auto v = text(name);
  if (!v) throw error(name, "is required");
  return *v;
}

UsageError ParsedArgs::error(std::string_view name, std::string_view problem) const {
  return usage(command_, "--" + std::string(name) + " " + std::string(problem));
}

std::optional<std::int64_t> ParsedArgs::integer(std::string_view name, std::int64_t lo,
                                                std::int64_t hi) const {
  const auto v = text(name);
  if (!v) return std::nullopt;
  std::int64_t n = 0;
  const auto [end, ec] = std::from_chars(v->data(), v->data() + v->size(), n);
  if (ec != std::errc{} || end != v->data() + v->size()) {
    throw error(name, "expects an integer, got '" + *v + "'");
  }
  if (n < lo || n > hi) {
    throw error(name,
                "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + *v);
  }
  return n;
}

std::optional<double> parse_real(std::string_view text) {
  double x = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(x)) {
    return std::nullopt;
  }
  return x;
}

std::optional<double> ParsedArgs::real(std::string_view name, double lo, double hi) const {
  const auto v = text(name);
  if (!v) return std::nullopt;
  const auto x = parse_real(*v);
  if (!x) throw error(name, "expects a number, got '" + *v + "'");
  if (*x < lo || *x > hi) throw error(name, "is out of range: " + *v);
  return x;
}

ParsedArgs parse_args(std::string_view command, std::span<char* const> args,
                      std::span<const FlagSpec> specs) {
  std::map<std::string, std::string> values;
  for (std::size_t k = 0; k < args.size(); ++k) {
    std::string word = args[k];
    if (!word.starts_with("--")) throw usage(command, "unexpected argument '" + word + "'");
    std::string name = word.substr(2);
    std::optional<std::string> inline_value;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name.resize(eq);
    }
    const FlagSpec* spec = find_spec(specs, name);
    if (name == "help") {
      values["help"] = "";
      continue;
    }
    if (spec == nullptr)
      throw usage(command, "unknown flag '--" + name + "'" + suggest(specs, name));
    if (spec->value.empty()) {
      if (inline_value) throw usage(command, "--" + name + " takes no value");
      values[name] = "";
    } else if (inline_value) {
      values[name] = *inline_value;
    } else if (k + 1 < args.size()) {
      values[name] = args[++k];
    } else {
      throw usage(command, "--" + name + " needs a value (" + std::string(spec->value) + ")");
    }
  }
  return ParsedArgs(std::string(command), std::move(values));
}

void print_help(std::ostream& out, std::string_view usage_line, std::string_view about,
                std::span<const FlagSpec> specs) {
  out << "usage: " << usage_line << "\n\n" << about << "\n\nflags:\n";
  for (const FlagSpec& s : specs) {
    std::string left = "--";
    left.append(s.name);
    if (!s.value.empty()) left.append(" ").append(s.value);
    // A flag wider than the column gets its help on the next line, not glued to it.
    if (left.size() >= 26) left.append("\n").append(28, ' ');
    out << "  " << std::left << std::setw(26) << left << s.help << '\n';
  }
  out << "  " << std::left << std::setw(26) << "--help"
      << "print this help\n";
}

std::optional<Pose2> pose_flag(const ParsedArgs& args, std::string_view name) {
  const std::optional<std::string> text = args.text(name);
  if (!text) return std::nullopt;
  std::array<double, 3> v{};
  std::size_t start = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t comma = k < 2 ? text->find(',', start) : text->size();
    if (comma == std::string::npos) throw args.error(name, "expects X,Y,THETA");
    const auto x = parse_real(std::string_view(*text).substr(start, comma - start));
    if (!x) throw args.error(name, "expects three numbers X,Y,THETA, got '" + *text + "'");
    v[k] = *x;
    start = comma + 1;
  }
  return Pose2{v[0], v[1], wrap_angle(v[2])};
}

}  // namespace mote::tool
