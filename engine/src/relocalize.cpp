// Re-localization: what the filter does once the localization state says it is lost
// (localization_state.hpp). It replaces augmented MCL's injection (Thrun et al., table 8.3) in
// mote's defaults: injection replaced particles update after update for as long as the scans
// fitted worse than their long-term average, KLD grew the set with every injected bin, and a
// hard stretch of data made each update cost a global initialization's for hundreds of updates
// while the filter was not lost at all.
#include <algorithm>

#include "localizer_impl.hpp"
#include "mote/engine/recovery.hpp"

namespace mote {
namespace {

// Lost updates in a row before the first re-localization: the smoothed see-through share has
// crossed the bound and stayed there for this many scans, so one odd scan does not trigger it.
constexpr int kFirstAfter = 3;
// Each re-localization that did not end the lost stretch doubles the wait before the next,
// up to this many lost updates: a filter on the wrong map pays a global update every 96
// updates at most, not every update.
constexpr int kLongestWait = 96;
// Share of the belief the particles already there keep: a hypothesis that still explains the
// scans (a false alarm, a crowd) then outweighs every fresh particle at a look-alike place by
// the ratio of the set sizes, and loses to the fresh particles only where the scans favour
// them.
constexpr double kKeptWeight = 0.5;

}  // namespace

void Localizer::Impl::reset_relocalization() {
  lost_updates = 0;
  relocalize_after = kFirstAfter;
  relocalize_due = false;
  settled_once = false;
}

void Localizer::Impl::count_lost_updates() {
  if (stats.state != LocalizationState::kLost) {
    lost_updates = 0;
    if (stats.state == LocalizationState::kTracking) relocalize_after = kFirstAfter;
    return;
  }
  ++lost_updates;
  // Before the belief has settled once (a global start converging, a wrong map) it is global
  // already: a global set would only restart the search.
  if (!config.relocalize_when_lost || !settled_once || lost_updates < relocalize_after) return;
  relocalize_due = true;
  lost_updates = 0;
  relocalize_after = std::min(2 * relocalize_after, kLongestWait);
}

void Localizer::Impl::maybe_relocalize() {
  if (!relocalize_due) return;
  relocalize_due = false;
  const std::size_t before = store.size();
  append_uniform(store, global_count(), kKeptWeight, map, config.seed, step, config.grain);
  stats.relocalized = store.size() - before;
  monitor.reset();
}

}  // namespace mote
