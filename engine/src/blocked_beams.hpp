#pragma once
// Beams blocked by something the map does not hold (people, carts, a crowd around the robot),
// found before the scan is weighed and left out of it. Internal.

#include <cstddef>
#include <vector>

#include "field_walker.hpp"
#include "map_field.hpp"
#include "mote/engine/beams.hpp"
#include "mote/engine/estimate.hpp"
#include "mote/engine/particles.hpp"

namespace mote {

// Mean range of the readings of `beams` that have an endpoint (0 when none has): the scale of
// the scan.
[[nodiscard]] double mean_endpoint_range(const BeamSet& beams);

/// The distance filter of Fox, Burgard and Thrun ("Markov localization for mobile robots in
/// dynamic environments", JAIR 11, 1999) on the map's distance field. A reading z
/// is blocked at a pose when the map holds no obstacle along the beam up to z + band: the beam
/// stopped short of where the map says it ends, by more than the miss at which the hit term
/// z_hit N(z - z*; 0, sigma_hit^2) falls below the random floor z_rand / z_max (Thrun eqs. 6.4,
/// 6.11); that is what the beam model's z_short term explains. An endpoint within sigma_hit of a
/// wall is never blocked, and a reading past a wall is not either (a map error or a wrong pose,
/// which the weighting must see). The probability that a beam is blocked is the belief's weight on
/// the poses where it is, over an even stride sample of the predicted particles (the belief before
/// this scan, as in Fox et al.); a beam that most of the belief finds blocked is left out for every
/// particle, once the belief has settled on a few places (focused()). Dropping it for all
/// particles alike favours none of them, unlike weighing it with the likelihood field, where a
/// crowd's readings reward whichever wrong pose puts a wall at 0.5 m. With z_rand = 0 no reading is
/// ever random and the filter drops nothing.
class BlockedBeamFilter {
 public:
  /// Particles evaluated at most.
  static constexpr std::size_t kSample = 64;
  /// Share of the belief that must find a beam blocked for it to be left out: a majority. Fox
  /// et al. drop a reading at 0.99, but of the probability that the beam model's short term
  /// explains it; here it is the share of a 64-particle sample whose ray runs free past the
  /// reading, which the cloud's own spread keeps below 0.99 for most crowd readings: at 0.99
  /// the Intel crowd (mote crowd) carried the filter off (ATE 3.72 m against 0.058 m at 0.5).
  /// What a wrong but tight belief drops is still partly seen: the localization state's hit
  /// share judges every reading at the refined pose; its see-through share judges the weighed
  /// beams (see_through.hpp), which this filter has thinned.
  static constexpr double kAgreement = 0.5;
  /// Share of the belief that settled hypotheses must hold for the filter to run (focused()).
  static constexpr double kFocusedWeight = 0.9;

  /// Removes the blocked beams from `beams` (keeping their order); returns how many it removed.
  /// `map` supplies the map, its distance field and the sensor mixture; `focused` is focused()
  /// of the belief before this scan, as the Localizer judged it once for the whole update
  /// (the state and tracking tempering read the same verdict). Nothing is removed unless it is.
  /// `places`: the poses of the places the belief holds (one per place, from the last update;
  /// empty or one when it holds one). Where it holds several, a beam is left out only when
  /// each place that holds a tenth of the sample's weight or more finds it blocked by a
  /// majority of its own: a reading blocked at one place but ending on a wall at another is
  /// what tells them apart (the pillar that only one of two look-alike wings holds read as
  /// blocked at the heavier twin and was dropped for every particle, so the scans could never
  /// tell the wings apart).
  std::size_t operator()(BeamSet& beams, const ConstParticleView& particles, const MapField& map,
                         bool focused, const std::vector<Pose2>& places = {});

  /// Whether the belief has settled closely enough to say where the walls are: clusters that
  /// each hold at least 1 - kFocusedWeight of it and whose spread moves a typical endpoint by
  /// less than the hit band hold kFocusedWeight of it together. Two tight hypotheses count, as
  /// in Fox et al., where the probability that a beam is blocked sums over the whole belief:
  /// gating on the heaviest cluster alone switched the filter off just when a look-alike pose
  /// 25 m down the Wean corridor drew level with the right one, as a few scans there read short
  /// of the map (scan fit 0.69 against 0.92), and the short readings then handed the wrong pose
  /// the belief (seed 4). A diffuse belief (global localization, or its many small clusters
  /// after the first resampling) finds most short readings "blocked" at its many open poses,
  /// yet those readings are what tells the poses apart.
  [[nodiscard]] static bool focused(const std::vector<PoseEstimate>& clusters, double band,
                                    double range);
  /// focused() at the hit band of the map's mixture and the mean range of the endpoints of beams.
  [[nodiscard]] static bool focused_on(const BeamSet& beams, const MapField& map,
                                       const std::vector<PoseEstimate>& clusters);
  /// The belief's places at the scale of the scan, the mean range of the endpoints of beams
  /// (the localization state's test of one hypothesis). Its hypotheses (clusters of 1 -
  /// kFocusedWeight of the weight or more) are grouped, each with the first heavier one it is
  /// not another place from (HypothesisHold::other_place at that range); `one`: a single place,
  /// where focused() at that scale holds. A hypothesis whose spread moves an endpoint by less
  /// than the scan reaches is one place that the scan match resolves; a wider one is a region
  /// of the building, as a fresh global set is (its heading spread alone, pi / sqrt(3) rad,
  /// moves an endpoint by 1.8 ranges). The hit band would be the wrong scale here: adaptive
  /// tempering and the odometry noise before its fit widen the cloud to 0.6 m and 19 degrees at
  /// the start of the Edmonton log while the refined pose is within 0.06 m of the reference,
  /// and the state read `uncertain` for its first 50 s. Two tight clusters at look-alike
  /// places 12 m apart (Wean's corridors) pass focused() together, and a global search that
  /// ended there read `tracking` at one of them.
  struct Places {
    std::size_t count = 0;
    bool one = false;
    std::vector<Pose2> anchors;  // each place's heaviest hypothesis (count of them)
  };
  [[nodiscard]] static Places places_on(const BeamSet& beams,
                                        const std::vector<PoseEstimate>& clusters);
  /// Position standard deviation plus heading standard deviation times `range`: how far the
  /// cluster's spread moves an endpoint at that range.
  [[nodiscard]] static double endpoint_spread(const PoseEstimate& cluster, double range);

 private:
  // One sampled particle: its sensor in grid-frame cell units, the cosine and sine of its
  // heading in the grid frame, and its weight.
  struct SensorSample {
    Point2 origin;
    double cos_theta = 1.0;
    double sin_theta = 0.0;
    double weight = 0.0;
    std::size_t place = 0;  // index of the nearest of `places`
  };
  // Beam b's unit direction in the grid frame at sample s: the sample's heading plus the
  // beam's angle, by angle addition (no trigonometry per pair).
  [[nodiscard]] Point2 direction(std::size_t b, const SensorSample& s) const;
  // Whether beam b's endpoint at sample s lies within sigma_hit (m) of a wall, or off the map.
  [[nodiscard]] bool ends_on_wall(const BeamSet& beams, std::size_t b, const SensorSample& s,
                                  const FieldWalker& walk, double sigma_hit) const;
  // Whether the map holds no obstacle along beam b at sample s up to its reading plus the hit
  // band (m): the beam is blocked there (given that its endpoint is not on a wall).
  [[nodiscard]] bool ray_free(const BeamSet& beams, std::size_t b, const SensorSample& s,
                              const FieldWalker& walk, double band) const;
  // Whether more than kAgreement of the samples' weight finds beam b blocked (at most 64
  // samples: kSample).
  [[nodiscard]] bool majority_blocked(const BeamSet& beams, std::size_t b, const MapField& map,
                                      double band) const;
  // Whether every place holding a tenth of the samples' weight or more finds beam b blocked by
  // more than kAgreement of its own samples' weight (several places).
  [[nodiscard]] bool blocked_at_every_place(const BeamSet& beams, std::size_t b,
                                            const MapField& map, double band) const;

  static constexpr std::size_t kBeamGrain = 16;  // beams per parallel task

  std::vector<SensorSample> samples_;
  std::vector<double> beam_cos_;  // per beam: cosine and sine of its angle in the sensor frame
  std::vector<double> beam_sin_;
  std::vector<unsigned char> drop_;  // per beam: 1 when left out
  double total_ = 0.0;               // the samples' weight
  std::vector<double> place_total_;  // per place: its samples' weight
};

}  // namespace mote
