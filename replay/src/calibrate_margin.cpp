// The online odometry noise's margin, chosen by how well the scans fit the map at the filter's
// estimates (calibrate.hpp, MarginTrial, says why that and not the residuals).
#include <numbers>

#include "mote/core/error.hpp"
#include "mote/replay/calibrate.hpp"

namespace mote::replay {
namespace {

MarginTrial run(const MarginScorer& score, double margin) {
  MarginTrial t = score(margin);
  t.margin = margin;
  return t;
}

// From `from`, one factor at a time while the fit improves and the margin stays in range.
void climb(const MarginScorer& score, MarginTrial from, double factor, double min, double max,
           std::vector<MarginTrial>& trials) {
  for (;;) {
    const double next = from.margin * factor;
    if (next < min * (1 - 1e-9) || next > max * (1 + 1e-9)) return;
    const MarginTrial t = run(score, next);
    trials.push_back(t);
    if (!(t.fit > from.fit)) return;
    from = t;
  }
}

}  // namespace

std::vector<MarginTrial> search_margin(const MarginScorer& score, double start, double min,
                                       double max) {
  if (!(min > 0.0) || !(max >= min) || !(start >= min && start <= max)) {
    throw Error("search_margin: expected 0 < min <= start <= max");
  }
  std::vector<MarginTrial> trials{run(score, start)};
  climb(score, trials.front(), std::numbers::sqrt2, min, max, trials);
  // Down from the start only when the step up did not help: a fit that rose upward peaks above.
  const bool rose = trials.size() > 1 && trials[1].fit > trials.front().fit;
  if (!rose) climb(score, trials.front(), 1.0 / std::numbers::sqrt2, min, max, trials);
  return trials;
}

const MarginTrial& best_margin(const std::vector<MarginTrial>& trials) {
  if (trials.empty()) throw Error("best_margin: no margin was tried");
  const MarginTrial* best = &trials.front();
  for (const MarginTrial& t : trials) {
    if (t.fit > best->fit) best = &t;
  }
  return *best;
}

}  // namespace mote::replay
