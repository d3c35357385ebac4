#pragma once
/// \file
/// The refined estimate's share of an update: the scan match the Localizer runs once per update
/// on the best hypothesis, timed alone on the end-to-end benchmark's drive.

namespace mote::bench {

/// Registers BM_ScanMatch_Refine/beams:<b> for every beam count of the suite.
void register_refine_cases();

}  // namespace mote::bench
