#include "blocked_beams.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>

#include "field_walker.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/hypothesis_hold.hpp"

namespace mote {
namespace {

// The miss |z - z*| beyond which a reading is more probably random than a hit: where
// z_hit N(d; 0, sigma_hit^2) falls to z_rand / z_max (Thrun eq. 6.4 against eq. 6.11). 0 when
// the hit term never rises above the floor, +inf when there is no floor (z_rand = 0).
double hit_band(const MixtureParams& m, double range_max) {
  if (!(m.z_rand > 0.0)) return std::numeric_limits<double>::infinity();
  const double peak = m.z_hit / (m.sigma_hit * std::sqrt(2.0 * std::numbers::pi));
  const double ratio = peak / (m.z_rand / range_max);
  return ratio > 1.0 ? m.sigma_hit * std::sqrt(2.0 * std::log(ratio)) : 0.0;
}

// Index of the pose in `places` nearest to p (0 when there is none).
std::size_t nearest(const std::vector<Pose2>& places, const Pose2& p) {
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < places.size(); ++k) {
    const double d = std::hypot(places[k].x - p.x, places[k].y - p.y);
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best;
}

}  // namespace

double mean_endpoint_range(const BeamSet& beams) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const float r : beams.range) {
    if (!(r < beams.range_max)) continue;
    sum += r;
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

Point2 BlockedBeamFilter::direction(std::size_t b, const SensorSample& s) const {
  return {s.cos_theta * beam_cos_[b] - s.sin_theta * beam_sin_[b],
          s.sin_theta * beam_cos_[b] + s.cos_theta * beam_sin_[b]};
}

bool BlockedBeamFilter::ends_on_wall(const BeamSet& beams, std::size_t b, const SensorSample& s,
                                     const FieldWalker& walk, double sigma_hit) const {
  // An endpoint within sigma_hit of a wall is a hit wherever the ray went (the likelihood
  // field scores it near its peak). Off the map counts as on a wall: nothing to trace.
  const double k = walk.inv_cell();
  const double r = beams.range[b] * k;
  const Point2 u = direction(b, s);
  const double near_wall = std::max(sigma_hit * k, 1.5);
  return walk.cells_to_wall({s.origin.x + r * u.x, s.origin.y + r * u.y}) < near_wall;
}

bool BlockedBeamFilter::ray_free(const BeamSet& beams, std::size_t b, const SensorSample& s,
                                 const FieldWalker& walk, double band) const {
  // Traced first past the endpoint (where a wall within the band ends most rays), then up to it.
  const double k = walk.inv_cell();
  const double r = beams.range[b];
  const Point2 u = direction(b, s);
  const double beyond = std::min(r + band, static_cast<double>(beams.range_max));
  return walk.free(s.origin, u, r * k, beyond * k) && walk.free(s.origin, u, 0.0, r * k);
}

bool BlockedBeamFilter::majority_blocked(const BeamSet& beams, std::size_t b, const MapField& map,
                                         double band) const {
  if (!(beams.range[b] < beams.range_max)) return false;  // a no-return has no endpoint
  const FieldWalker walk(map.grid, map.signed_field);
  const double needed = kAgreement * total_;
  // The samples whose endpoint lies on a wall first (a lookup each), then rays traced for the
  // others until the answer is settled: the same answer as in any order, as each sample's
  // verdict is its own.
  double clear = 0.0;
  static_assert(kSample <= 64, "a bit per sample");
  std::uint64_t traced = 0;  // bit i: sample i needs its ray traced
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    if (ends_on_wall(beams, b, samples_[i], walk, map.mixture.sigma_hit)) {
      clear += samples_[i].weight;
    } else {
      traced |= std::uint64_t{1} << i;
    }
  }
  if (clear >= total_ - needed) return false;
  double blocked = 0.0;
  for (; traced != 0; traced &= traced - 1) {
    const SensorSample& s = samples_[static_cast<std::size_t>(std::countr_zero(traced))];
    (ray_free(beams, b, s, walk, band) ? blocked : clear) += s.weight;
    if (blocked > needed) return true;
    if (clear >= total_ - needed) return false;
  }
  return false;
}

double BlockedBeamFilter::endpoint_spread(const PoseEstimate& cluster, double range) {
  const Eigen::Matrix3d& c = cluster.covariance;
  return std::sqrt(c(0, 0) + c(1, 1)) + std::sqrt(c(2, 2)) * range;
}

bool BlockedBeamFilter::focused(const std::vector<PoseEstimate>& clusters, double band,
                                double range) {
  // A cluster of a tenth of the weight or more is a hypothesis; the many small clusters of a
  // diffuse set are not, however tight each one's few particles are.
  constexpr double kHypothesisWeight = 1.0 - kFocusedWeight;
  double settled = 0.0;
  for (const PoseEstimate& c : clusters) {
    if (c.weight >= kHypothesisWeight && endpoint_spread(c, range) < band) settled += c.weight;
  }
  return settled >= kFocusedWeight;
}

BlockedBeamFilter::Places BlockedBeamFilter::places_on(const BeamSet& beams,
                                                       const std::vector<PoseEstimate>& clusters) {
  constexpr double kHypothesisWeight = 1.0 - kFocusedWeight;
  const double range = mean_endpoint_range(beams);
  std::vector<Pose2> anchors;  // the heaviest hypothesis of each place (clusters: heaviest first)
  for (const PoseEstimate& c : clusters) {
    if (c.weight < kHypothesisWeight) continue;
    const bool known = std::any_of(anchors.begin(), anchors.end(), [&](const Pose2& a) {
      return !HypothesisHold::other_place(a, c.mean, range);
    });
    if (!known) anchors.push_back(c.mean);
  }
  const bool one = anchors.size() == 1 && focused(clusters, range, range);
  return {.count = anchors.size(), .one = one, .anchors = std::move(anchors)};
}

bool BlockedBeamFilter::focused_on(const BeamSet& beams, const MapField& map,
                                   const std::vector<PoseEstimate>& clusters) {
  return focused(clusters, hit_band(map.mixture, beams.range_max), mean_endpoint_range(beams));
}

bool BlockedBeamFilter::blocked_at_every_place(const BeamSet& beams, std::size_t b,
                                               const MapField& map, double band) const {
  if (!(beams.range[b] < beams.range_max)) return false;
  const FieldWalker walk(map.grid, map.signed_field);
  std::vector<double> blocked(place_total_.size(), 0.0);
  for (const SensorSample& s : samples_) {
    if (ends_on_wall(beams, b, s, walk, map.mixture.sigma_hit)) continue;
    if (ray_free(beams, b, s, walk, band)) blocked[s.place] += s.weight;
  }
  bool any = false;
  for (std::size_t k = 0; k < place_total_.size(); ++k) {
    if (place_total_[k] < (1.0 - kFocusedWeight) * total_) continue;
    if (!(blocked[k] > kAgreement * place_total_[k])) return false;
    any = true;
  }
  return any;
}

std::size_t BlockedBeamFilter::operator()(BeamSet& beams, const ConstParticleView& p,
                                          const MapField& map, bool focused,
                                          const std::vector<Pose2>& places) {
  const std::size_t n = p.size();
  const double band = hit_band(map.mixture, beams.range_max);
  if (n == 0 || beams.empty() || !std::isfinite(band)) return 0;
  if (!focused) return 0;
  const FieldWalker walk(map.grid, map.signed_field);
  samples_.clear();
  total_ = 0.0;
  const std::size_t stride = std::max<std::size_t>(1, (n + kSample - 1) / kSample);
  const double grid_theta = map.grid.origin().theta;  // the grid frame's heading in the map's
  for (std::size_t i = 0; i < n; i += stride) {
    const double w = std::exp(static_cast<double>(p.logw[i]));
    if (!(w > 0.0) || !is_finite(p.pose(i))) continue;
    const Pose2 sensor = compose(p.pose(i), beams.sensor_pose);
    const double theta = sensor.theta - grid_theta;
    samples_.push_back({walk.cell_point({sensor.x, sensor.y}), std::cos(theta), std::sin(theta), w,
                        nearest(places, p.pose(i))});
    total_ += w;
  }
  place_total_.assign(std::max<std::size_t>(1, places.size()), 0.0);
  for (const SensorSample& s : samples_) place_total_[s.place] += s.weight;
  if (!(total_ > 0.0)) return 0;
  beam_cos_.resize(beams.size());
  beam_sin_.resize(beams.size());
  for (std::size_t b = 0; b < beams.size(); ++b) {
    beam_cos_[b] = std::cos(static_cast<double>(beams.angle[b]));
    beam_sin_[b] = std::sin(static_cast<double>(beams.angle[b]));
  }
  // Beams are independent: decided in parallel, each by its own fixed sample order.
  drop_.assign(beams.size(), 0);
  par::for_each_chunk(beams.size(), kBeamGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b) {
      drop_[b] = places.size() > 1 ? blocked_at_every_place(beams, b, map, band)
                                   : majority_blocked(beams, b, map, band);
    }
  });
  std::size_t kept = 0;
  for (std::size_t b = 0; b < beams.size(); ++b) {
    if (drop_[b] != 0) continue;
    beams.angle[kept] = beams.angle[b];
    beams.range[kept] = beams.range[b];
    ++kept;
  }
  const std::size_t removed = beams.size() - kept;
  beams.angle.resize(kept);
  beams.range.resize(kept);
  return removed;
}

}  // namespace mote
