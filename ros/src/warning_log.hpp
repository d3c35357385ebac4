#pragma once
/// \file
/// Counted, rate-limited warnings of a long-running process: each kind of problem is counted
/// every time and printed at most once per interval, with how many were not printed.

#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <string>

namespace mote::ros::detail {

class WarningLog {
 public:
  using Clock = std::chrono::steady_clock;
  /// `sink` gets each printed line; `interval` is the least time between two of one kind.
  WarningLog(std::function<void(const std::string&)> sink, Clock::duration interval)
      : sink_(std::move(sink)), interval_(interval) {}

  /// Counts one `kind` (e.g. "malformed /scan") and prints `text` unless that kind printed
  /// within the interval. Thread-safe.
  void warn(const std::string& kind, const std::string& text);
  /// Prints a line now, uncounted (start-up and state notices).
  void notice(const std::string& text);
  /// How many of `kind` were counted.
  [[nodiscard]] std::size_t count(const std::string& kind) const;

 private:
  struct Kind {
    std::size_t count = 0;
    std::size_t unprinted = 0;
    Clock::time_point last{};
    bool printed = false;
  };
  std::function<void(const std::string&)> sink_;
  Clock::duration interval_;
  mutable std::mutex mutex_;
  std::map<std::string, Kind> kinds_;
};

}  // namespace mote::ros::detail
