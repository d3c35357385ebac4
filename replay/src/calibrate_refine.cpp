// Scan-to-map alignment of one pose: Nelder-Mead on the beam model's scan log-likelihood, the
// expected ranges ray cast (Embree) at every trial pose.
#include "calibrate_refine.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "calibrate_minimize.hpp"

namespace mote::replay::detail {

Refined refine_pose(const RayCaster& caster, const LaserScan& scan, const Pose2& start, double z_hit,
                  double sigma, double range_max, std::size_t step) {
  const double floor = (1.0 - z_hit) / range_max;
  const double norm = z_hit / (std::sqrt(2.0 * std::numbers::pi) * sigma);
  const auto max_range = static_cast<float>(range_max);
  std::size_t inside = 0, used = 0;
  auto cost = [&](const std::vector<double>& p) {
    inside = used = 0;
    const Pose2 robot{start.x + p[0], start.y + p[1], start.theta + p[2]};
    const Pose2 sensor = compose(robot, scan.sensor_pose);
    double sum = 0;
    for (std::size_t b = step / 2; b < scan.ranges.size(); b += step) {
      const double z = scan.ranges[b];
      if (!(z >= scan.range_min) || z >= range_max) continue;
      const double e = z - caster.cast_one({sensor.x, sensor.y}, sensor.theta + scan.beam_angle(b), max_range);
      sum -= std::log(norm * std::exp(-0.5 * e * e / (sigma * sigma)) + floor);
      ++used;
      inside += std::abs(e) < 3 * sigma ? 1U : 0U;
    }
    return sum;
  };
  // Offsets from the start, bounded: a refinement, not a search for a lost robot.
  const std::vector<Bounded> box{{0.0, -0.3, 0.3, false}, {0.0, -0.3, 0.3, false}, {0.0, -0.15, 0.15, false}};
  int evaluations = 0;
  const std::vector<double> best = minimize(cost, box, 400, evaluations);
  (void)cost(best);  // the inlier count at the result
  return {{start.x + best[0], start.y + best[1], wrap_angle(start.theta + best[2])},
          used == 0 ? 0.0 : static_cast<double>(inside) / static_cast<double>(used)};
}

}  // namespace mote::replay::detail
