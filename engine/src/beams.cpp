#include "mote/engine/beams.hpp"

#include <algorithm>
#include <cmath>

namespace mote {

namespace {

float effective_min(const LaserScan& scan, double configured) {
  return configured >= 0.0 ? static_cast<float>(configured) : scan.range_min;
}

// Unlike amcl, a configured maximum never exceeds the scan's own: readings the sensor marks as
// "no return" (e.g. CARMEN's 81.83 m) must stay max-range readings whatever the config says.
float effective_max(const LaserScan& scan, double configured) {
  if (configured <= 0.0) return scan.range_max;
  const auto c = static_cast<float>(configured);
  return scan.range_max > 0.0F ? std::min(c, scan.range_max) : c;
}

enum class Reading { kInvalid, kValid, kMaxRange };

Reading classify(float r, float range_min, float range_max) {
  if (std::isnan(r) || r < 0.0F || r < range_min) return Reading::kInvalid;
  if (r >= range_max) return Reading::kMaxRange;  // includes +inf
  return Reading::kValid;
}

}  // namespace

void select_beams(const LaserScan& scan, const BeamSelection& selection, BeamSet& out) {
  out.angle.clear();
  out.range.clear();
  out.sensor_pose = scan.sensor_pose;
  out.range_min = effective_min(scan, selection.range_min);
  out.range_max = effective_max(scan, selection.range_max);
  out.readings = scan.size();

  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Reading kind = classify(scan.ranges[i], out.range_min, out.range_max);
    if (kind == Reading::kInvalid || (kind == Reading::kMaxRange && !selection.keep_max_range)) {
      continue;
    }
    out.angle.push_back(static_cast<float>(scan.beam_angle(i)));
    out.range.push_back(kind == Reading::kMaxRange ? out.range_max : scan.ranges[i]);
  }
  out.valid = out.angle.size();

  const auto max_beams = static_cast<std::size_t>(std::max(selection.max_beams, 1));
  if (out.valid <= max_beams) return;
  // Keep survivor floor(k * valid / max_beams) for k = 0..max_beams-1: evenly spaced, in place.
  for (std::size_t k = 0; k < max_beams; ++k) {
    const std::size_t src = k * out.valid / max_beams;
    out.angle[k] = out.angle[src];
    out.range[k] = out.range[src];
  }
  out.angle.resize(max_beams);
  out.range.resize(max_beams);
}

}  // namespace mote
