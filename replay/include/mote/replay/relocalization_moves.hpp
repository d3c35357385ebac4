#pragma once
/// \file
/// What each re-localization of a run did to the reported pose: whether the filter settled
/// again (read `tracking`) and how far from where it stood before, carried by the odometry,
/// it settled. A re-localization that settles where the tracked hypothesis was is a false
/// alarm ridden out; one that settles far from it moved the pose a planner would act on (a
/// kidnapping found, or a jump to a place one scan fitted: the reference tells which).

#include <cstddef>
#include <vector>

#include "mote/replay/replay_run.hpp"

namespace mote::replay {

/// m: a re-localization moved the reported pose when it settled farther than this from the
/// pose before it carried there by the odometry. The bound the accuracy table calls a lost run
/// (scripts/accuracy-table): a move below it is the filter's own correction, not a new place.
inline constexpr double kMovedPoseM = 1.0;

/// One re-localization.
struct RelocalizationMove {
  std::size_t update = 0;  ///< index in ReplayResult::updates of the update that added it
  /// Index of the first tracking update after it (before any later re-localization), or
  /// updates.size() when the run never tracked again before the next one or the end.
  std::size_t settled_update = 0;
  /// m, distance between the pose reported at settled_update and the pose reported before the
  /// re-localization carried there by the odometry; NaN when it never settled or when it ran
  /// on the first update (no pose before it).
  double moved_m = 0.0;
};

/// The re-localizations of a run.
struct RelocalizationMoves {
  std::vector<RelocalizationMove> moves;
  std::size_t moved = 0;      ///< moves with moved_m > kMovedPoseM
  std::size_t unsettled = 0;  ///< moves that never read tracking again
};

/// The re-localizations of `updates` (one record per update that ran, in order).
[[nodiscard]] RelocalizationMoves relocalization_moves(const std::vector<UpdateRecord>& updates);

}  // namespace mote::replay
