// updates.csv: what the filter decided at every update, for plotting beside the trajectory.
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "mote/core/error.hpp"
#include "mote/replay/report.hpp"

namespace mote::replay {
namespace {

// A stamp as trajectory.tum writes it (write_tum, nanoseconds): ROS stamps (1.66e9 s) keep
// every digit, so the two files join on the text.
std::string full(double stamp) {
  std::array<char, 48> buf{};
  const int n = std::snprintf(buf.data(), buf.size(), "%.9f", stamp);
  return {buf.data(), static_cast<std::size_t>(std::max(n, 0))};
}

}  // namespace

void write_updates_csv(const std::filesystem::path& file, const ReplayResult& result) {
  std::ofstream out(file);
  out << "stamp,particles,weighed,beams,blocked_beams,ess,tempering,log_evidence,"
         "injected,relocalized,resampled,alpha1,alpha2,alpha3,alpha4,total_ms,state,hit_share,"
         "see_through,misfit,refined_x,refined_y,refined_theta,mean_x,mean_y,mean_theta,places,"
         "held,switched,lost_bound\n";
  out.precision(10);
  for (std::size_t k = 0; k < result.updates.size(); ++k) {
    const UpdateRecord& u = result.updates[k];
    // A result assembled by hand (tests, Python) may leave the particle trajectory empty.
    constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
    const Pose2 mean = k < result.particle_trajectory.size() ? result.particle_trajectory[k].pose
                                                             : Pose2{kNan, kNan, kNan};
    out << full(u.stamp) << ',' << u.particles << ',' << u.weighed << ',' << u.beams << ','
        << u.blocked_beams << ',' << u.effective_sample_size << ',' << u.tempering << ','
        << u.log_evidence << ',' << u.injected << ',' << u.relocalized << ','
        << (u.resampled ? 1 : 0) << ',' << u.alphas.alpha1 << ',' << u.alphas.alpha2 << ','
        << u.alphas.alpha3 << ',' << u.alphas.alpha4 << ',' << u.ms.total << ',' << name_of(u.state)
        << ',' << u.hit_share << ',' << u.see_through << ',' << u.misfit << ',' << u.refined.x
        << ',' << u.refined.y << ',' << u.refined.theta << ',' << mean.x << ',' << mean.y << ','
        << mean.theta << ',' << u.places << ',' << (u.held ? 1 : 0) << ',' << (u.switched ? 1 : 0)
        << ',' << u.lost_bound << '\n';
  }
  if (!out.good()) throw Error(file.string() + ": cannot write");
}

}  // namespace mote::replay
