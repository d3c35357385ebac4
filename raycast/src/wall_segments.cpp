#include "wall_segments.hpp"

#include <algorithm>
#include <cstddef>

#include "mote/core/parallel.hpp"

namespace mote::detail {

namespace {

/// Grid lines per block: each block's runs go to a list of its own.
constexpr std::size_t kLinesPerBlock = 256;

/// The runs of blocks of `lines` grid lines, each block's written by block(begin, end, out) in
/// parallel, joined in block order: the list the serial walk gives, for any thread count.
template <class Block>
std::vector<WallSegment> in_blocks(int lines, const Block& block) {
  const auto n = static_cast<std::size_t>(lines);
  std::vector<std::vector<WallSegment>> parts((n + kLinesPerBlock - 1) / kLinesPerBlock);
  par::for_each_chunk(parts.size(), /*grain=*/1, [&](std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) {
      block(static_cast<int>(b * kLinesPerBlock),
            static_cast<int>(std::min(n, (b + 1) * kLinesPerBlock)), parts[b]);
    }
  });
  std::vector<WallSegment> out;
  std::size_t total = 0;
  for (const auto& part : parts) total += part.size();
  out.reserve(total);
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

/// Maximal runs of edges along horizontal grid lines [j0, j1); line j separates row j - 1
/// (below) from row j (above). Both rows are read in memory order.
void horizontal_runs(const CellMask& mask, int j0, int j1, std::vector<WallSegment>& out) {
  const auto coord = [&mask](int k) { return static_cast<float>(mask.line(k)); };
  for (int j = j0; j < j1; ++j) {
    int i = 0;
    while (i < mask.width) {
      const auto edge = [&](int c) {
        return mask.blocks_or_free(c, j - 1) != mask.blocks_or_free(c, j);
      };
      if (!edge(i)) {
        ++i;
        continue;
      }
      const int begin = i;
      while (i < mask.width && edge(i)) ++i;
      out.push_back({coord(begin), coord(j), coord(i), coord(j)});
    }
  }
}

/// Maximal runs of edges along vertical grid lines [i0, i1); line i separates column i - 1
/// (left) from column i (right). The rows are walked in memory order with each line's open run
/// kept aside, then the runs are ordered line by line as a walk down each line gives them.
void vertical_runs(const CellMask& mask, int i0, int i1, std::vector<WallSegment>& out) {
  const auto coord = [&mask](int k) { return static_cast<float>(mask.line(k)); };
  std::vector<int> open(static_cast<std::size_t>(i1 - i0), -1);  // first row of the open run
  const auto close = [&](int i, int end) {
    int& begin = open[static_cast<std::size_t>(i - i0)];
    out.push_back({coord(i), coord(begin), coord(i), coord(end)});
    begin = -1;
  };
  for (int j = 0; j < mask.height; ++j) {
    for (int i = i0; i < i1; ++i) {
      const bool edge = mask.blocks_or_free(i - 1, j) != mask.blocks_or_free(i, j);
      int& begin = open[static_cast<std::size_t>(i - i0)];
      if (edge && begin < 0) {
        begin = j;
      } else if (!edge && begin >= 0) {
        close(i, j);
      }
    }
  }
  for (int i = i0; i < i1; ++i) {
    if (open[static_cast<std::size_t>(i - i0)] >= 0) close(i, mask.height);
  }
  // Within a line the runs were closed in row order; stable, the sort keeps that order.
  std::stable_sort(out.begin(), out.end(),
                   [](const WallSegment& a, const WallSegment& b) { return a.x0 < b.x0; });
}

}  // namespace

std::vector<WallSegment> wall_segments(const CellMask& mask) {
  std::vector<WallSegment> out = in_blocks(
      mask.height + 1, [&](int j0, int j1, auto& part) { horizontal_runs(mask, j0, j1, part); });
  const std::vector<WallSegment> vertical = in_blocks(
      mask.width + 1, [&](int i0, int i1, auto& part) { vertical_runs(mask, i0, i1, part); });
  out.insert(out.end(), vertical.begin(), vertical.end());
  return out;
}

}  // namespace mote::detail
