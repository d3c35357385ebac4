#include "wall_segments.hpp"

namespace mote::detail {

namespace {

/// Appends the maximal runs of boundary edges on one grid line. `is_edge(k)` says whether edge k
/// (k in [0, count)) of the line separates blocking from non-blocking; `emit(begin, end)` adds
/// the run of edges [begin, end).
template <class IsEdge, class Emit>
void merge_runs(int count, const IsEdge& is_edge, const Emit& emit) {
  int k = 0;
  while (k < count) {
    if (!is_edge(k)) {
      ++k;
      continue;
    }
    const int begin = k;
    while (k < count && is_edge(k)) ++k;
    emit(begin, k);
  }
}

}  // namespace

std::vector<WallSegment> wall_segments(const CellMask& mask) {
  std::vector<WallSegment> out;
  const auto coord = [&mask](int n) { return static_cast<float>(mask.line(n)); };
  // Horizontal grid line j separates row j - 1 (below) from row j (above).
  for (int j = 0; j <= mask.height; ++j) {
    merge_runs(
        mask.width,
        [&](int i) { return mask.blocks_or_free(i, j - 1) != mask.blocks_or_free(i, j); },
        [&](int begin, int end) {
          out.push_back({coord(begin), coord(j), coord(end), coord(j)});
        });
  }
  // Vertical grid line i separates column i - 1 (left) from column i (right).
  for (int i = 0; i <= mask.width; ++i) {
    merge_runs(
        mask.height,
        [&](int j) { return mask.blocks_or_free(i - 1, j) != mask.blocks_or_free(i, j); },
        [&](int begin, int end) {
          out.push_back({coord(i), coord(begin), coord(i), coord(end)});
        });
  }
  return out;
}

}  // namespace mote::detail
