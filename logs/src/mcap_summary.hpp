#pragma once
/// \file
/// An MCAP file's footer and summary section (mcap.dev/spec, "Summary Section"): where the data
/// section ends, the schemas and channels, and the chunk indexes, read before any chunk.

#include <cstdint>
#include <vector>

#include "mcap_file.hpp"

namespace mote::logs::detail::mcap {

struct Summary {
  bool has_footer = false;     ///< the file ends with a footer and the closing magic
  bool has_summary = false;    ///< the footer points at a summary section
  bool unchunked = false;      ///< its statistics count no chunks (messages are top level)
  std::uint64_t data_end = 0;  ///< where the data section ends (summary, footer or end of file)
  std::vector<Schema> schemas;
  std::vector<Channel> channels;
  std::vector<ChunkIndex> chunks;  ///< in message start time order (stable)
};

/// Reads the footer and, when it points at one, the summary; checks the summary CRC when the
/// footer carries one. Throws BagDecodeError with file offsets. A file without the closing
/// magic (cut short) has no footer: data_end is the end of the file.
Summary read_summary(McapFile& file);

}  // namespace mote::logs::detail::mcap
