// The verdict on a run from its per-update localization states.
#include "mote/replay/verdict.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace mote::replay {

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
  // The verdict reads the last kVerdictUpdates updates, not the last one: a single scan through
  // a doorway the map draws closed reads lost for an update or two on a run that is where it
  // should be (Wean), while a wrong map or an unrecovered kidnapping stays lost through the
  // re-localizations' back-off (relocalize.cpp), over most of the window.
  const std::size_t window = std::min(kVerdictUpdates, result.updates.size());
  std::size_t lost_in_window = 0;
  for (std::size_t k = result.updates.size() - window; k < result.updates.size(); ++k) {
    lost_in_window += result.updates[k].state == LocalizationState::kLost ? 1 : 0;
  }
  v.localized = 2 * lost_in_window <= window;
  v.window = window;
  v.lost_at_end = lost_in_window;
  std::size_t lost = 0;
  std::size_t since = result.updates.size();  // first update of the final stretch without lost
  for (std::size_t k = result.updates.size(); k-- > 0;) {
    if (result.updates[k].state == LocalizationState::kLost) break;
    since = k;
  }
  for (const UpdateRecord& u : result.updates) lost += u.state == LocalizationState::kLost ? 1 : 0;
  if (v.final_state == LocalizationState::kTracking && since < result.updates.size()) {
    v.tracking_since_s = result.updates[since].stamp - result.first_stamp;
  }
  if (!v.localized) {
    const double share =
        100.0 * static_cast<double>(lost) / static_cast<double>(result.updates.size());
    v.warning = "the run ends lost: the scans do not fit the map around the estimate (lost on " +
                std::to_string(lost_in_window) + " of the last " + std::to_string(window) +
                " updates, " + std::to_string(static_cast<int>(std::lround(share))) +
                " % of all). A map of another place, a wrong laser frame or range, or a "
                "kidnapping the filter has not recovered from";
  }
  return v;
}

std::vector<std::pair<std::string, std::string>> verdict_rows(const RunVerdict& v) {
  if (!v.ran) return {{"localized", "no: " + v.warning}};
  std::array<char, 160> buf{};
  if (v.localized) {
    if (v.tracking_since_s) {
      std::snprintf(buf.data(), buf.size(), "yes, tracking since %.1f s", *v.tracking_since_s);
    } else {
      std::snprintf(buf.data(), buf.size(), "yes, %zu of the last %zu updates lost, ends %s",
                    v.lost_at_end, v.window, name_of(v.final_state));
    }
  } else {
    std::snprintf(buf.data(), buf.size(), "NO, ends lost (see the warning)");
  }
  std::string localized = buf.data();
  std::snprintf(buf.data(), buf.size(), "x %.3f m, y %.3f m, theta %.3f rad at %.3f s",
                v.final_pose.x, v.final_pose.y, v.final_pose.theta, v.final_stamp);
  return {{"localized", localized}, {"final pose", buf.data()}};
}

void write_verdict_json(JsonWriter& json, const RunVerdict& v) {
  json.key("verdict").begin_object();
  json.member("localized", v.localized);
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
