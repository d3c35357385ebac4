#pragma once
// A progress bar on stderr for long replays, drawn only when stderr is a terminal.

#include <cstddef>
#include <filesystem>
#include <functional>

#include "mote/logs/scan_source.hpp"

namespace mote::tool {

/// Counts the scans in a log (a cheap first pass) so the bar can show a fraction; 0 if unknown.
[[nodiscard]] std::size_t count_scans(const std::filesystem::path& log,
                                      const logs::ReaderOptions& options);

/// A callback drawing `[#####.....] scans/total` on stderr, or an empty function when stderr is
/// not a terminal. finish_progress() ends the line.
[[nodiscard]] std::function<void(std::size_t)> make_progress(const std::filesystem::path& log,
                                                             const logs::ReaderOptions& options);
void finish_progress(const std::function<void(std::size_t)>& bar);

}  // namespace mote::tool
