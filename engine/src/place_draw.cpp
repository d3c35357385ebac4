// Look-alike places resampled in equal numbers (localizer_impl.hpp, resample_by_place).
//
// A mixture particle filter (Vermaak, Doucet and Perez, "Maintaining multi-modality through
// mixture tracking", ICCV 2003): each place the belief holds is a component with a weight of
// its own. Drawn by weight, a place's particle count follows its weight, and its weight after
// the next scan is the mean likelihood of those few particles: a noisy estimate that random
// walks the place's share down until it has no particle left, on two identical floors as
// surely as on different ones. Here each place is drawn with the same count whatever its
// weight, and each of its particles carries W_k n / n_k afterwards: an importance-weighted draw
// (the proposal's shares, corrected by target / proposal), so the places' shares are exactly
// what the scans made them and only their representation changes.
#include <algorithm>
#include <cmath>

#include "localizer_impl.hpp"
#include "mote/core/parallel.hpp"
#include "mote/engine/resample.hpp"
#include "mote/engine/weights.hpp"
#include "weight_sums.hpp"

namespace mote {
namespace {

// The label of a particle at none of the places: drawn by its weight as before.
constexpr std::uint8_t kNoPlace = 255;
// At most this many places are drawn evenly (labels fit a byte with kNoPlace to spare; a
// place holds a tenth of the belief when it is counted, so there are at most ten).
constexpr std::size_t kMaxEvenPlaces = 16;

}  // namespace

void Localizer::Impl::label_places() {
  const ParticleView p = store.view();
  place_label.resize(p.size());
  std::uint8_t* label = place_label.data();
  const std::vector<Pose2>& places = even_places;
  const double range = scan_range;
  par::for_each_chunk(p.size(), config.grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Pose2 pose = p.pose(i);
      const auto at = std::find_if(places.begin(), places.end(), [&](const Pose2& place) {
        return !HypothesisHold::other_place(place, pose, range);
      });
      label[i] = at == places.end() ? kNoPlace : static_cast<std::uint8_t>(at - places.begin());
    }
  });
}

std::vector<double> Localizer::Impl::place_weights() const {
  const ConstParticleView p = std::as_const(store).view();
  const std::uint8_t* label = place_label.data();
  const std::size_t places = even_places.size();
  std::vector<double> w(places + 1);  // the last: the particles at no place
  for (std::size_t k = 0; k <= places; ++k) {
    const auto mine = static_cast<std::uint8_t>(k == places ? kNoPlace : k);
    // Fixed-block sums: the same for any thread count and grain.
    w[k] = detail::sum_weights(p.size(), 0.0F, [p, label, mine](std::size_t i) {
             return label[i] == mine ? p.logw[i] : detail::kNegInfF;
           }).w;
  }
  return w;
}

void Localizer::Impl::scale_by_place(const std::vector<double>& factor) {
  const ParticleView p = store.view();
  std::vector<float> log_factor(factor.size());
  std::transform(factor.begin(), factor.end(), log_factor.begin(),
                 [](double f) { return static_cast<float>(std::log(f)); });
  const std::uint8_t* label = place_label.data();
  const std::size_t none = factor.size() - 1;
  par::for_each_chunk(p.size(), config.grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      p.logw[i] += log_factor[label[i] == kNoPlace ? none : label[i]];
    }
  });
}

void Localizer::Impl::place_prior(const Pose2& odometry) {
  even_places.clear();
  // Once settled, as keep_places: a global search's clusters come and go with every scan.
  const std::size_t k = place_anchors.size();
  if (!has_odometry || !has_held || k < 2 || k > kMaxEvenPlaces || !(scan_range > 0.0)) return;
  const Pose2 moved = between(last_odometry, odometry);
  even_places.resize(k);
  std::transform(place_anchors.begin(), place_anchors.end(), even_places.begin(),
                 [&](const Pose2& anchor) { return compose(anchor, moved); });
  label_places();
  prior_place_weight = place_weights();
}

void Localizer::Impl::weigh_places() {
  place_weight.clear();
  place_log_bayes.clear();
  // A scan that explained no particle reset the weights to uniform: no evidence, and the even
  // draw's counts would read as the places' shares.
  if (even_places.empty() || degenerate) return;
  place_weight = place_weights();
  // Place k's Bayes factor against the best place (the heaviest after the scan): (W_k / P_k) /
  // (W_best / P_best), its weight after the scan over before, each over the best's, in the
  // filter's tempered weights; NaN where a place had no weight.
  const std::size_t k = even_places.size();
  const std::vector<double>& prior = prior_place_weight;
  const std::vector<double>& post = place_weight;
  const auto best = static_cast<std::size_t>(
      std::max_element(post.begin(), post.begin() + static_cast<std::ptrdiff_t>(k)) - post.begin());
  place_log_bayes.assign(k, std::nan(""));
  if (!(post[best] > 0.0) || !(prior[best] > 0.0)) return;
  const double best_gain = std::log(post[best] / prior[best]);
  for (std::size_t j = 0; j < k; ++j) {
    if (post[j] > 0.0 && prior[j] > 0.0)
      place_log_bayes[j] = std::log(post[j] / prior[j]) - best_gain;
  }
}

void Localizer::Impl::resample_by_place(const KldConfig& per_place) {
  // The places drawn evenly: those the scan did not refute. Below a Bayes factor of e^-5 against
  // the best place (kVeryStrongEvidence) the scan has told the places apart, and the place is
  // drawn by its weight. What the particles' luck does to a place's weight is a factor of a few per
  // scan (a floor of 25 identical copies: 0.2-5), what a scan of another place does is 1e-6 and
  // less (Intel kidnapped).
  const std::vector<double>& weight = place_weight;
  std::vector<bool> even(place_log_bayes.size());
  std::transform(place_log_bayes.begin(), place_log_bayes.end(), even.begin(),
                 [](double log_b) { return log_b >= kVeryStrongEvidence; });
  const auto drawn_evenly = static_cast<double>(std::count(even.begin(), even.end(), true));
  // Augmented MCL's injection replaces the particles at or below 1/N weight, as after a plain
  // draw; after an even one those are the lighter places' particles, which it would eat: with
  // its rates set, the plain draw.
  if (drawn_evenly < 2.0 || recovery.enabled()) {
    resample_kld_systematic(store, bins, per_place, config.seed, step, config.grain);
    return;
  }
  double mass = 0.0;
  for (std::size_t j = 0; j < even.size(); ++j) mass += even[j] ? weight[j] : 0.0;
  // The proposal: the mass of the unrefuted places split evenly between them, the rest as it
  // was. to_draw scales the weights before the draw, and its inverse restores each place's
  // weight after it.
  std::vector<double> to_draw(weight.size(), 1.0);
  std::vector<double> back(weight.size(), 1.0);
  for (std::size_t j = 0; j < even.size(); ++j) {
    if (!even[j]) continue;
    to_draw[j] = mass / drawn_evenly / weight[j];
    back[j] = 1.0 / to_draw[j];
  }
  scale_by_place(to_draw);
  resample_kld_systematic(store, bins, per_place, config.seed, step, config.grain);
  label_places();  // a copy sits where its ancestor did: the same label
  scale_by_place(back);
  // The systematic draw gives each place its share to within a particle: renormalize.
  mote::normalize(store.view(), config.grain);
}

}  // namespace mote
