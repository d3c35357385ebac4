#pragma once
/// \file
/// Message counts per topic, time span, storage and tf frames of a log, per format.

#include "mote/replay/log_info.hpp"

namespace mote::replay::detail {

/// Fills format, storage, compression, files, start/end, messages, topics and frames.
[[nodiscard]] LogInfo count_messages(const std::filesystem::path& path,
                                     const ReaderOptions& options);

}  // namespace mote::replay::detail
