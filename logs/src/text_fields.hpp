#pragma once
/// \file
/// Whitespace-separated fields of one text line with checked number parsing; every failure
/// throws InputError naming the file, the line and the field (design.md section 3).

#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "mote/core/error.hpp"

namespace mote::logs::detail {

/// Cursor over the fields of one line.
class LineFields {
 public:
  LineFields(std::string_view line, const std::string& file, std::size_t line_no)
      : file_(file), line_no_(line_no) {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !is_space(line[i])) ++i;
      if (i > start) fields_.push_back(line.substr(start, i - start));
    }
  }

  [[nodiscard]] std::size_t size() const noexcept { return fields_.size(); }
  [[nodiscard]] bool empty() const noexcept { return fields_.empty(); }
  [[nodiscard]] std::size_t remaining() const noexcept { return fields_.size() - next_; }
  [[nodiscard]] std::string_view peek(std::size_t k) const { return fields_.at(k); }

  /// Throws unless exactly `count` fields remain.
  void expect_remaining(std::size_t count, std::string_view what) const {
    if (remaining() != count) {
      fail(std::string(what) + ": expected " + std::to_string(count) + " more fields, found " +
           std::to_string(remaining()));
    }
  }

  /// The next field as text.
  std::string_view word(std::string_view what) {
    if (next_ >= fields_.size()) fail("missing field '" + std::string(what) + "'");
    return fields_[next_++];
  }

  /// The next field as a finite number.
  double finite(std::string_view what) {
    const std::string_view text = word(what);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(value)) {
      fail("field '" + std::string(what) + "': expected a finite number, found '" +
           std::string(text) + "'");
    }
    return value;
  }

  /// The next field as an integer in [lo, hi].
  long long integer(std::string_view what, long long lo, long long hi) {
    const std::string_view text = word(what);
    long long value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || value < lo || value > hi) {
      fail("field '" + std::string(what) + "': expected an integer in [" + std::to_string(lo) +
           ", " + std::to_string(hi) + "], found '" + std::string(text) + "'");
    }
    return value;
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_, "line " + std::to_string(line_no_), problem);
  }

 private:
  static bool is_space(char c) noexcept { return c == ' ' || c == '\t' || c == '\r'; }

  std::vector<std::string_view> fields_;
  std::size_t next_ = 0;
  const std::string& file_;
  std::size_t line_no_;
};

}  // namespace mote::logs::detail
