// updates.csv: what the filter decided at every update, for plotting beside the trajectory.
#include <fstream>

#include "mote/core/error.hpp"
#include "mote/replay/report.hpp"

namespace mote::replay {

void write_updates_csv(const std::filesystem::path& file, const ReplayResult& result) {
  std::ofstream out(file);
  out << "stamp,particles,weighed,beams,blocked_beams,ess,tempering,log_evidence,"
         "injected,relocalized,resampled,alpha1,alpha2,alpha3,alpha4,total_ms,state,hit_share,"
         "see_through,misfit,refined_x,refined_y,refined_theta\n";
  out.precision(10);
  for (const UpdateRecord& u : result.updates) {
    out << u.stamp << ',' << u.particles << ',' << u.weighed << ',' << u.beams << ','
        << u.blocked_beams << ',' << u.effective_sample_size << ',' << u.tempering << ','
        << u.log_evidence << ',' << u.injected << ',' << u.relocalized << ','
        << (u.resampled ? 1 : 0) << ',' << u.alphas.alpha1 << ',' << u.alphas.alpha2 << ','
        << u.alphas.alpha3 << ',' << u.alphas.alpha4 << ',' << u.ms.total << ',' << name_of(u.state)
        << ',' << u.hit_share << ',' << u.see_through << ',' << u.misfit << ',' << u.refined.x
        << ',' << u.refined.y << ',' << u.refined.theta << '\n';
  }
  if (!out.good()) throw Error(file.string() + ": cannot write");
}

}  // namespace mote::replay
