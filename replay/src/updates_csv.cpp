// updates.csv: what the filter decided at every update, for plotting beside the trajectory.
#include <fstream>

#include "mote/core/error.hpp"
#include "mote/replay/report.hpp"

namespace mote::replay {

void write_updates_csv(const std::filesystem::path& file, const ReplayResult& result) {
  std::ofstream out(file);
  out << "stamp,particles,weighed,beams,blocked_beams,ess,tempering,scan_fit,log_evidence,"
         "injected,resampled,alpha1,alpha2,alpha3,alpha4,total_ms\n";
  out.precision(10);
  for (const UpdateRecord& u : result.updates) {
    out << u.stamp << ',' << u.particles << ',' << u.weighed << ',' << u.beams << ','
        << u.blocked_beams << ',' << u.effective_sample_size << ',' << u.tempering << ','
        << u.scan_fit << ',' << u.log_evidence << ',' << u.injected << ',' << (u.resampled ? 1 : 0)
        << ',' << u.alphas.alpha1 << ',' << u.alphas.alpha2 << ',' << u.alphas.alpha3 << ','
        << u.alphas.alpha4 << ',' << u.ms.total << '\n';
  }
  if (!out.good()) throw Error(file.string() + ": cannot write");
}

}  // namespace mote::replay
