#pragma once
/// \file
/// The suggestion in "unknown flag '--partcles' (did you mean '--particles'?)": the known word
/// closest to a misspelled one by edit distance (Levenshtein: insertions, deletions and
/// substitutions of one character each cost 1), when it is close enough to be a typo.

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <string>
#include <string_view>
#include <vector>

namespace mote {

/// Levenshtein distance between a and b (two-row dynamic programme, O(|a| |b|)).
[[nodiscard]] inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

/// The candidate closest to `word`, or "" when none is within a third of the word's length
/// (at least 2 edits): further than that it is another word, not a typo of one. Ties go to the
/// first candidate, so the answer is deterministic.
template <typename Range>
[[nodiscard]] std::string closest_word(std::string_view word, const Range& candidates) {
  const std::size_t allowed = std::max<std::size_t>(2, word.size() / 3);
  std::string best;
  std::size_t best_distance = allowed + 1;
  for (const auto& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(candidate);
    }
  }
  return best;
}

}  // namespace mote
