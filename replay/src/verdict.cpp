// The verdict on a run from its per-update localization states.
#include "mote/replay/verdict.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace mote::replay {
namespace {

// Index of the first update of the run's last unbroken stretch in `state` (size() if the last
// update is in another state).
std::size_t final_stretch_start(const ReplayResult& result, LocalizationState state) {
  std::size_t since = result.updates.size();
  for (std::size_t k = result.updates.size(); k-- > 0;) {
    if (result.updates[k].state != state) break;
    since = k;
  }
  return since;
}

double seconds_at(const ReplayResult& result, std::size_t k) {
  return result.updates[k].stamp - result.first_stamp;
}

std::string lost_warning(std::size_t lost_in_window, std::size_t window, std::size_t lost,
                         std::size_t updates) {
  const double share = 100.0 * static_cast<double>(lost) / static_cast<double>(updates);
  std::string text =
      "the run ends lost: the scans do not fit the map around the estimate (lost on ";
  text.append(std::to_string(lost_in_window))
      .append(" of the last ")
      .append(std::to_string(window))
      .append(" updates, ")
      .append(std::to_string(static_cast<int>(std::lround(share))))
      .append(
          " % of all). A map of another place, a wrong laser frame or range, or a kidnapping "
          "the filter has not recovered from");
  return text;
}

std::string unsure_warning(std::size_t lost_last, std::size_t window) {
  std::string text = "the last ";
  text.append(std::to_string(lost_last))
      .append(" updates are lost, too few of the last ")
      .append(std::to_string(window))
      .append(
          " to call the run lost (exit status 0): a place the map does not show (clutter, "
          "a door drawn closed) or a kidnapping at the end; the final pose may be wrong");
  return text;
}

}  // namespace

RunVerdict judge_run(const ReplayResult& result) {
  RunVerdict v;
  if (result.updates.empty() || result.trajectory.empty()) {
    v.warning = "no filter update ran: the log has no scan with odometry the filter could use";
    return v;
  }
  v.ran = true;
  v.final_state = result.updates.back().state;
  v.final_pose = result.trajectory.back().pose;
  v.final_stamp = result.trajectory.back().stamp;
  v.stamp_source = result.stamp_source;
  // The verdict reads the last kVerdictUpdates updates, not the last one: a single scan through
  // a doorway the map draws closed reads lost for an update or two on a run that is where it
  // should be (Wean), while a wrong map or an unrecovered kidnapping stays lost through the
  // re-localizations' back-off (relocalize.cpp), over most of the window. A run whose last
  // updates are lost is not called localized, though: that would contradict its end state.
  const std::size_t n = result.updates.size();
  const std::size_t window = std::min(kVerdictUpdates, n);
  std::size_t lost_in_window = 0;
  for (std::size_t k = n - window; k < n; ++k) {
    lost_in_window += result.updates[k].state == LocalizationState::kLost ? 1 : 0;
  }
  const bool few_lost = 2 * lost_in_window <= window;
  const bool ends_lost = v.final_state == LocalizationState::kLost;
  v.localized = few_lost && !ends_lost;
  v.unsure = few_lost && ends_lost;
  v.window = window;
  v.lost_at_end = lost_in_window;
  v.lost_last = ends_lost ? n - final_stretch_start(result, LocalizationState::kLost) : 0;
  if (v.final_state == LocalizationState::kTracking) {
    v.tracking_since_s =
        seconds_at(result, final_stretch_start(result, LocalizationState::kTracking));
  }
  if (v.unsure) {
    for (std::size_t k = n - v.lost_last; k-- > 0;) {
      if (result.updates[k].state != LocalizationState::kTracking) continue;
      v.tracking_until_s = seconds_at(result, k);
      break;
    }
    v.warning = unsure_warning(v.lost_last, window);
  } else if (!v.localized) {
    std::size_t lost = 0;
    for (const UpdateRecord& u : result.updates)
      lost += u.state == LocalizationState::kLost ? 1 : 0;
    v.warning = lost_warning(lost_in_window, window, lost, n);
  }
  return v;
}

int exit_status(const RunVerdict& v) noexcept {
  return v.localized || v.unsure ? 0 : kExitEndsLost;
}

std::vector<std::pair<std::string, std::string>> verdict_rows(const RunVerdict& v) {
  if (!v.ran) return {{"localized", "no: " + v.warning}};
  std::array<char, 200> buf{};
  if (v.localized && v.tracking_since_s) {
    std::snprintf(buf.data(), buf.size(), "yes, tracking since %.1f s", *v.tracking_since_s);
  } else if (v.localized) {
    std::snprintf(buf.data(), buf.size(), "yes, %zu of the last %zu updates lost, ends %s",
                  v.lost_at_end, v.window, name_of(v.final_state));
  } else if (v.unsure && v.tracking_until_s) {
    std::snprintf(buf.data(), buf.size(),
                  "unsure: tracking until %.1f s, then lost on the last %zu updates (%zu of the "
                  "last %zu lost; see the warning)",
                  *v.tracking_until_s, v.lost_last, v.lost_at_end, v.window);
  } else if (v.unsure) {
    std::snprintf(buf.data(), buf.size(),
                  "unsure: lost on the last %zu updates (%zu of the last %zu lost; see the "
                  "warning)",
                  v.lost_last, v.lost_at_end, v.window);
  } else {
    std::snprintf(buf.data(), buf.size(), "NO, ends lost (see the warning)");
  }
  std::string localized = buf.data();
  std::snprintf(buf.data(), buf.size(), "x %.3f m, y %.3f m, theta %.3f rad at %.3f s",
                v.final_pose.x, v.final_pose.y, v.final_pose.theta, v.final_stamp);
  std::string final_pose = buf.data();
  // Which clock: a bag's scan header stamps can be hours from the record times `mote info`'s
  // duration spans.
  if (!v.stamp_source.empty()) final_pose.append(" (").append(v.stamp_source).append(")");
  return {{"localized", localized}, {"final pose", final_pose}};
}

std::string capped_global_set_text(const ReplayResult& r) {
  std::size_t relocalizations = 0;
  for (const UpdateRecord& u : r.updates) relocalizations += u.relocalized > 0 ? 1 : 0;
  if (!r.global_set.capped || (!r.global_start && relocalizations == 0)) return "";
  std::string which = r.global_start ? "the global start" : "";
  if (relocalizations > 0) {
    which.append(r.global_start ? " and " : "")
        .append(std::to_string(relocalizations))
        .append(relocalizations == 1 ? " re-localization" : " re-localizations");
  }
  std::array<char, 120> figures{};
  std::snprintf(figures.data(), figures.size(),
                ": %zu particles, %.2f per KLD bin (asked %.1f); raise max_particles",
                r.global_set.particles, r.global_set.per_bin, r.config.global_particles_per_bin);
  std::string text = "capped at max_particles for ";
  text.append(which).append(figures.data());
  if (r.global_set.per_bin < 1.0) {
    // Most bins hold no particle: a place the draw missed (a look-alike copy of the one the
    // belief settles on included) is found only by a later re-localization.
    text.append(
        "; with fewer than one particle per bin most of the map's poses were not drawn, "
        "so the belief can miss the true place among look-alike ones");
  }
  return text;
}

void write_verdict_json(JsonWriter& json, const RunVerdict& v) {
  json.key("verdict").begin_object();
  json.member("localized", v.localized);
  json.member("unsure", v.unsure);
  json.member("final_state", v.ran ? name_of(v.final_state) : "none");
  json.member("tracking_since_s", v.tracking_since_s);
  if (v.ran) {
    json.key("final_pose").begin_object();
    json.member("stamp", v.final_stamp).member("x", v.final_pose.x);
    json.member("y", v.final_pose.y).member("theta", v.final_pose.theta);
    json.end_object();
  }
  json.member("warning", v.warning);
  json.end_object();
}

}  // namespace mote::replay
