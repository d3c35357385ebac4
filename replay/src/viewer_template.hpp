#pragma once
// The parts of viewer.html around the embedded data (viewer_page.cpp puts them together).
#include <array>
#include <string_view>

namespace mote::replay {

/// Doctype, head with the style sheet, and the body's elements, up to the data block.
extern const std::string_view kViewerPageHead;
/// The page's script, in four parts that make one function scope (the first opens it, the last
/// closes it and runs main()): helpers and the tables of states, phases and timelines
/// (viewer_script.cpp); the map, its axes and the trajectory coloured by state
/// (viewer_script_map.cpp); the timelines, the state band and the time axis
/// (viewer_script_timelines.cpp); main(), which decodes the data block (id "mote-data") and
/// draws the update shown (viewer_script_main.cpp).
extern const std::string_view kViewerScriptHead;
extern const std::string_view kViewerScriptMap;
extern const std::string_view kViewerScriptTimelines;
extern const std::string_view kViewerScriptMain;

/// The script's parts in page order.
inline std::array<std::string_view, 4> viewer_script_parts() {
  return {kViewerScriptHead, kViewerScriptMap, kViewerScriptTimelines, kViewerScriptMain};
}

}  // namespace mote::replay
