#include "scan_fit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mote {

ScanFit::ScanFit(const OccupancyGrid& grid, const MixtureParams& mixture, double max_distance)
    : grid_(grid),
      field_(grid,
             {.unknown_is_obstacle = false, .max_distance = static_cast<float>(max_distance)}),
      mixture_(mixture),
      max_distance_(static_cast<float>(max_distance)) {}

void ScanFit::build_table(float range_max) {
  const auto log_density = [&](float d) {
    return static_cast<float>(std::log(likelihood_field_density(d, range_max, mixture_)));
  };
  const std::vector<float>& d = field_.distances();
  log_density_.resize(d.size());
  for (std::size_t c = 0; c < d.size(); ++c) log_density_[c] = log_density(d[c]);
  off_map_ = log_density(max_distance_);
  table_range_max_ = range_max;
}

double ScanFit::operator()(const BeamSet& beams, const ConstParticleView& p) {
  const std::size_t n = p.size();
  if (n == 0) return 0.0;
  if (beams.range_max != table_range_max_) build_table(beams.range_max);
  // Endpoints in the robot frame once per scan (no-return beams have none to explain).
  std::vector<Point2> ends;
  ends.reserve(beams.size());
  const Pose2& s = beams.sensor_pose;
  for (std::size_t b = 0; b < beams.size(); ++b) {
    if (beams.range[b] >= beams.range_max) continue;
    const double a = s.theta + beams.angle[b];
    ends.push_back({s.x + beams.range[b] * std::cos(a), s.y + beams.range[b] * std::sin(a)});
  }
  if (ends.empty()) return 0.0;
  const std::size_t stride = std::max<std::size_t>(1, (n + kSample - 1) / kSample);
  double weighted = 0.0;
  double total = 0.0;
  for (std::size_t i = 0; i < n; i += stride) {
    const double w = std::exp(static_cast<double>(p.logw[i]));
    if (!(w > 0.0) || !is_finite(p.pose(i))) continue;
    weighted += w * std::exp(mean_log_density(ends, p.pose(i)));
    total += w;
  }
  return total > 0.0 ? weighted / total : 0.0;
}

double ScanFit::mean_log_density(const std::vector<Point2>& ends, const Pose2& pose) const {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  double sum = 0.0;
  for (const Point2& e : ends) {
    const CellIndex cell =
        grid_.world_to_cell({pose.x + c * e.x - s * e.y, pose.y + s * e.x + c * e.y});
    sum += grid_.contains(cell) ? log_density_[grid_.linear_index(cell)] : off_map_;
  }
  return sum / static_cast<double>(ends.size());
}

}  // namespace mote
