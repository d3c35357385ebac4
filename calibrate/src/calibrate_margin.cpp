// The online odometry noise's margin, chosen by how well the scans fit the map at the filter's
// estimates (calibrate.hpp, MarginTrial, says why that and not the residuals).
#include <cmath>
#include <cstdio>
#include <string>

#include "mote/calibrate/calibrate.hpp"
#include "mote/core/error.hpp"

namespace mote::calibrate {
namespace {

// start * sqrt(2)^k to three significant digits (4, 5.66, 8, 11.3, 16, ...): computed from k,
// not by repeated multiplication, and short enough that the config's %.6g writes it exactly.
double step(double start, int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", start * std::pow(2.0, 0.5 * k));
  return std::stod(buf);
}

MarginTrial run(const MarginScorer& score, double margin) {
  MarginTrial t = score(margin);
  t.margin = margin;
  t.accepted = false;
  return t;
}

// A step is taken only when its gain exceeds what the runs' disagreement calls noise: on a
// flat fit the margin stays where it is.
bool significantly_better(const MarginTrial& t, const MarginTrial& from) {
  return t.fit - from.fit > t.spread + from.spread;
}

// From the start, one sqrt(2) step in `dir` at a time while the fit improves and the margin
// stays in [min, max].
void climb(const MarginScorer& score, double start, const MarginTrial& from_trial, int dir,
           double min, double max, std::vector<MarginTrial>& trials) {
  MarginTrial from = from_trial;
  for (int k = dir;; k += dir) {
    const double next = step(start, k);
    if (next < min || next > max) return;
    MarginTrial t = run(score, next);
    t.accepted = significantly_better(t, from);
    trials.push_back(t);
    if (!t.accepted) return;
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
  trials.front().accepted = true;
  climb(score, start, trials.front(), +1, min, max, trials);
  // Down from the start only when the step up did not help: a fit that rose upward peaks above.
  const bool rose = trials.size() > 1 && trials[1].accepted;
  if (!rose) climb(score, start, trials.front(), -1, min, max, trials);
  return trials;
}

const MarginTrial& best_margin(const std::vector<MarginTrial>& trials) {
  const MarginTrial* best = nullptr;
  for (const MarginTrial& t : trials) {
    if (t.accepted && (best == nullptr || t.fit > best->fit)) best = &t;
  }
  if (best == nullptr) throw Error("best_margin: no margin was accepted");
  return *best;
}

}  // namespace mote::calibrate
