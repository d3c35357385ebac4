#pragma once
/// \file
/// A small streaming JSON writer for run reports: objects, arrays, strings, numbers, booleans and
/// null. Non-finite numbers are written as null, so the output is always valid JSON.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string_view>
#include <vector>

namespace mote::replay {

/// Writes indented JSON to a stream. Calls must nest correctly (key() only inside an object,
/// before each of its values); the writer adds commas, quotes and escapes.
class JsonWriter {
 public:
  /// Writes to `out`, which must outlive the writer.
  explicit JsonWriter(std::ostream& out) noexcept : out_(out) {}

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  /// The name of the next member of the current object.
  JsonWriter& key(std::string_view name);

  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  /// Shortest round-trip form; NaN and infinities become null.
  JsonWriter& value(double number);
  JsonWriter& value(std::int64_t number);
  JsonWriter& value(std::uint64_t number);
  JsonWriter& value(int number) { return value(static_cast<std::int64_t>(number)); }
  JsonWriter& value(bool flag);
  /// The number, or null when absent.
  JsonWriter& value(const std::optional<double>& number);
  JsonWriter& null();

  /// key(name).value(v) in one call.
  template <typename T>
  JsonWriter& member(std::string_view name, const T& v) {
    return key(name).value(v);
  }

 private:
  void before_value();
  void open(char bracket);
  void close(char bracket);
  void newline();

  std::ostream& out_;
  std::vector<bool> has_items_;  // one entry per open object or array
  bool after_key_ = false;
};

/// `text` as a quoted JSON string with escapes (control characters as \u00XX).
[[nodiscard]] std::string json_quote(std::string_view text);

}  // namespace mote::replay
