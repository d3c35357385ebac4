// The stderr progress bar of `mote replay`.
#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "mote/core/error.hpp"

namespace mote::tool {

std::size_t count_scans(const std::filesystem::path& log, const logs::ReaderOptions& options) {
  try {
    auto source = logs::open_scan_log(log, options);
    std::size_t n = 0;
    while (source->next()) ++n;
    return n;
  } catch (const Error&) {
    return 0;  // the replay itself reports the problem, with its place in the file
  }
}

std::function<void(std::size_t)> make_progress(const std::filesystem::path& log,
                                               const logs::ReaderOptions& options) {
  if (isatty(STDERR_FILENO) == 0) return {};
  const std::size_t total = count_scans(log, options);
  return [total, drawn = std::size_t{0}](std::size_t scans) mutable {
    constexpr std::size_t kWidth = 40;
    const std::size_t filled = total == 0 ? 0 : std::min(kWidth, scans * kWidth / total);
    if (scans != total && filled == drawn && scans % 100 != 0) return;
    drawn = filled;
    const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
    std::fprintf(stderr, "\r[%s] %zu/%zu scans", bar.c_str(), scans, total);
    std::fflush(stderr);
  };
}

void finish_progress(const std::function<void(std::size_t)>& bar) {
  if (bar) std::fputc('\n', stderr);
}

}  // namespace mote::tool
