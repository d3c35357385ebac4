#pragma once
/// \file
/// A machine check beside the end-to-end cases: a latency-bound and a vector-throughput-bound
/// compute loop on 1 and 2 threads. On a shared machine their 2-thread/1-thread ratios bound what
/// any case's ratio can show; where the vector loop scales less than the other, the two threads
/// share one core's vector units (hyperthreads).

namespace mote::bench {

/// Registers BM_Machine_{ComputeLoop,VectorLoop}/<when>/threads:{1,2} (`when`: "start" or
/// "end").
void register_machine_check(const char* when);

}  // namespace mote::bench
