#pragma once
/// \file
/// A machine check beside the end-to-end cases: a pure compute loop on 1 and 2 threads. On a
/// shared machine its 2-thread/1-thread ratio bounds what any case's ratio can show.

namespace mote::bench {

/// Registers BM_Machine_ComputeLoop/<when>/threads:{1,2} (`when`: "start" or "end").
void register_machine_check(const char* when);

}  // namespace mote::bench
