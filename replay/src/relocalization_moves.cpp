#include "mote/replay/relocalization_moves.hpp"

#include <cmath>
#include <limits>

#include "mote/core/pose.hpp"

namespace mote::replay {
namespace {

// The first tracking update after `from` and before the next re-localization (or the end).
std::size_t settled_after(const std::vector<UpdateRecord>& updates, std::size_t from) {
  for (std::size_t k = from; k < updates.size(); ++k) {
    if (k > from && updates[k].relocalized > 0) return updates.size();
    if (updates[k].state == LocalizationState::kTracking) return k;
  }
  return updates.size();
}

// The pose reported at update `before` moved by the odometry from there to update `to`.
Pose2 carried(const std::vector<UpdateRecord>& updates, std::size_t before, std::size_t to) {
  return compose(updates[before].refined, between(updates[before].odometry, updates[to].odometry));
}

}  // namespace

RelocalizationMoves relocalization_moves(const std::vector<UpdateRecord>& updates) {
  RelocalizationMoves out;
  for (std::size_t k = 0; k < updates.size(); ++k) {
    if (updates[k].relocalized == 0) continue;
    RelocalizationMove move{.update = k, .settled_update = settled_after(updates, k)};
    move.moved_m = std::numeric_limits<double>::quiet_NaN();
    if (move.settled_update == updates.size()) {
      ++out.unsettled;
    } else if (k > 0) {
      const Pose2 expected = carried(updates, k - 1, move.settled_update);
      const Pose2& reported = updates[move.settled_update].refined;
      move.moved_m = std::hypot(reported.x - expected.x, reported.y - expected.y);
      if (move.moved_m > kMovedPoseM) ++out.moved;
    }
    out.moves.push_back(move);
  }
  return out;
}

}  // namespace mote::replay
