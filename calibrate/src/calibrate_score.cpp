// How well the scans fit the map at given poses (calibrate_score.hpp), and scan_fit: the same
// score along a trajectory from a replay.
#include "calibrate_score.hpp"

#include <limits>
#include <numbers>

#include "mote/core/error.hpp"
#include "mote/maps/map_loader.hpp"

namespace mote::calibrate {
namespace detail {

std::vector<logs::ScanFrame> read_frames(const CalibrationOptions& o) {
  auto source = logs::open_scan_log(o.log, o.reader);
  std::vector<logs::ScanFrame> frames;
  while (auto f = source->next()) frames.push_back(std::move(*f));
  return frames;
}

double effective_range_max(const logs::ScanFrame& f, const LocalizerConfig& c) {
  const double r = f.scan.range_max;
  return c.laser_max_range > 0 ? std::min(r, c.laser_max_range) : r;
}

double endpoint_distance(const OccupancyGrid& map, const DistanceField& field, const Pose2& sensor,
                         double angle, double z, double max_d) {
  const Point2 end{sensor.x + z * std::cos(angle), sensor.y + z * std::sin(angle)};
  const CellIndex c = map.world_to_cell(end);
  const bool inside = c.i >= 0 && c.j >= 0 && c.i < map.width() && c.j < map.height();
  return inside ? std::min<double>(field.at(c), max_d) : max_d;
}

FieldMixture scoring_field(const CalibrationRound& last) {
  return {last.field.params.z_hit, last.field.params.z_rand,
          std::max(last.field.params.sigma_hit, last.beam.params.sigma_hit)};
}

MarginTrial endpoint_fit(const OccupancyGrid& map, const DistanceField& field,
                         const std::vector<logs::ScanFrame>& frames,
                         const std::vector<PosedFrame>& posed, const CalibrationOptions& o,
                         double range_max, const FieldMixture& m) {
  const double max_d = o.config.laser_likelihood_max_dist;
  const double norm = m.z_hit / (std::sqrt(2.0 * std::numbers::pi) * m.sigma_hit);
  double sum = 0.0;
  std::size_t scored = 0;
  for (const PosedFrame& p : posed) {
    const logs::ScanFrame& f = frames[p.frame];
    const Pose2 sensor = compose(p.pose, f.scan.sensor_pose);
    double scan_sum = 0.0;
    std::size_t beams = 0;
    for_fit_beams(f.scan, o.beams_per_scan, [&](std::size_t b, double z) {
      if (z >= range_max) return;
      const double d =
          endpoint_distance(map, field, sensor, sensor.theta + f.scan.beam_angle(b), z, max_d);
      scan_sum += std::log(norm * std::exp(-0.5 * d * d / (m.sigma_hit * m.sigma_hit)) +
                           m.z_rand / range_max);
      ++beams;
    });
    if (beams == 0) continue;
    sum += scan_sum / static_cast<double>(beams);
    ++scored;
  }
  const double mean =
      scored == 0 ? -std::numeric_limits<double>::infinity() : sum / static_cast<double>(scored);
  return {.margin = 0, .fit = mean, .poses = scored};
}

}  // namespace detail

double scan_fit(const CalibrationOptions& o, const CalibrationResult& r,
                const std::vector<logs::StampedPose>& trajectory) {
  if (r.rounds.empty()) throw Error("scan_fit: a calibration without rounds");
  const OccupancyGrid map = load_map(o.map);
  const std::vector<logs::ScanFrame> frames = detail::read_frames(o);
  if (frames.empty()) throw Error(o.log.string() + ": no scans");
  const DistanceField field(
      map, {.unknown_is_obstacle = false,
            .max_distance = static_cast<float>(o.config.laser_likelihood_max_dist)});
  // Both are in log order: pair each pose with the frame of its stamp.
  constexpr double kSameStamp = 1e-6;  // s
  std::vector<detail::PosedFrame> posed;
  std::size_t k = 0;
  for (const logs::StampedPose& p : trajectory) {
    while (k < frames.size() && frames[k].stamp < p.stamp - kSameStamp) ++k;
    if (k == frames.size()) break;
    if (std::abs(frames[k].stamp - p.stamp) <= kSameStamp) posed.push_back({k, p.pose, true, {}});
  }
  return detail::endpoint_fit(map, field, frames, posed, o,
                              detail::effective_range_max(frames.front(), o.config),
                              detail::scoring_field(r.rounds.back()))
      .fit;
}

}  // namespace mote::calibrate
