#include "warning_log.hpp"

namespace mote::ros::detail {

void WarningLog::warn(const std::string& kind, const std::string& text) {
  std::string line;
  {
    const std::lock_guard lock(mutex_);
    Kind& k = kinds_[kind];
    ++k.count;
    const Clock::time_point now = Clock::now();
    if (k.printed && now - k.last < interval_) {
      ++k.unprinted;
      return;
    }
    line = "warning: " + text;
    if (k.unprinted > 0) {
      line += " (" + std::to_string(k.unprinted) + " more like it not shown, " +
              std::to_string(k.count) + " in all)";
    }
    k.unprinted = 0;
    k.last = now;
    k.printed = true;
  }
  sink_(line);
}

void WarningLog::notice(const std::string& text) { sink_(text); }

std::size_t WarningLog::count(const std::string& kind) const {
  const std::lock_guard lock(mutex_);
  const auto it = kinds_.find(kind);
  return it == kinds_.end() ? 0 : it->second.count;
}

}  // namespace mote::ros::detail
