#pragma once
/// \file
/// When a lost filter re-localizes (adds a global set to its belief, relocalize_when_lost): the
/// rule behind the Localizer's re-localization, apart so that a sequence of states can be fed
/// to it directly.

#include <cstdint>

#include "mote/engine/localization_state.hpp"

namespace mote {

/// Counts lost updates and says when the next re-localization is due. The first comes after
/// kFirstAfter lost updates in a row; each one doubles the wait before the next, up to
/// kLongestWait lost updates in a row. Only a stretch of kTrackedToForgive tracking updates in a
/// row resets the wait: a filter that flaps (lost three updates, tracking one, as on Wean's
/// closed doors) would otherwise pay for a global set about every fourth update. After a global
/// start nothing is due before the belief has settled once: tracking once, or focused for
/// kConvergedAfter updates in a row (a search that converged where the scans do not fit);
/// before that the belief is a global search already (a global start converging, a wrong map)
/// and a global set would only restart it. A start around a given pose is settled from the
/// first update: Intel from a wrong `--init-pose 5,-20,1.5` stayed lost 20 m off for the whole
/// log when it had to settle first.
class RelocalizationSchedule {
 public:
  static constexpr std::uint64_t kFirstAfter = 3;
  static constexpr std::uint64_t kLongestWait = 96;
  static constexpr std::uint64_t kTrackedToForgive = 10;
  static constexpr std::uint64_t kConvergedAfter = 10;

  /// One update's state and whether its belief was focused; true when a re-localization is due
  /// before the next motion step (the wait then starts over, doubled).
  bool after_update(LocalizationState state, bool focused) noexcept;
  /// Forgets everything (after initialization). `settled`: the belief starts settled, as one
  /// around a pose the caller gave does (a start at a wrong pose is lost there, not searching);
  /// a global start does not.
  void reset(bool settled) noexcept {
    *this = RelocalizationSchedule{};
    settled_ = settled;
  }

  /// Whether the belief has settled once since the last reset().
  [[nodiscard]] bool settled() const noexcept { return settled_; }
  /// Lost updates in a row that the next re-localization waits for.
  [[nodiscard]] std::uint64_t wait() const noexcept { return wait_; }
  /// Whether the re-localization after_update() just called for searches around the belief:
  /// the first one after a stretch of kTrackedToForgive tracking updates (a belief that was
  /// right a moment ago; odometry that missed a turn leaves the robot near it). The ones after
  /// it, and any before the filter has tracked that long (a global start that settled at the
  /// wrong place, a wrong start pose), search the whole map.
  [[nodiscard]] bool local() const noexcept { return local_; }

 private:
  // Counters saturate rather than wrap on a run of years.
  static std::uint64_t next(std::uint64_t n, bool on) noexcept {
    return on ? n + (n < UINT64_MAX) : 0;
  }

  std::uint64_t lost_ = 0;     // lost updates in a row
  std::uint64_t tracked_ = 0;  // tracking updates in a row
  std::uint64_t focused_ = 0;  // focused updates in a row
  std::uint64_t wait_ = kFirstAfter;
  bool settled_ = false;
  bool trusted_ = false;  // tracked kTrackedToForgive in a row since the last re-localization
  bool local_ = false;
};

}  // namespace mote
