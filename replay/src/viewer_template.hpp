#pragma once
// The parts of viewer.html around the embedded data (viewer_page.cpp puts them together).
#include <string_view>

namespace mote::replay {

/// Doctype, head with the style sheet, and the body's elements, up to the data block.
extern const std::string_view kViewerPageHead;
/// The page's script: decodes the data block (id "mote-data") and draws map and timelines.
extern const std::string_view kViewerScript;

}  // namespace mote::replay
