#pragma once
/// \file
/// Message counts per topic, time span, storage and tf frames of a log, per format.

#include "mote/logs/log_info.hpp"

namespace mote::logs::detail {

/// Fills format, storage, compression, files, start/end, messages, topics and frames.
[[nodiscard]] LogInfo count_messages(const std::filesystem::path& path,
                                     const ReaderOptions& options);

}  // namespace mote::logs::detail
