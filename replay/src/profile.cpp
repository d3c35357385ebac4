#include "mote/replay/profile.hpp"

#include <cmath>
#include <limits>
#include <ostream>

#include "mote/replay/report_json.hpp"

namespace mote::replay {
namespace {

// The phase times of one update, in the order of RunProfile::phases.
constexpr std::array<std::string_view, 6> kPhaseNames{"motion",   "sensor",   "normalize",
                                                      "resample", "estimate", "other"};

std::array<double, 6> phase_times(const PhaseTimes& t) {
  const double phases = t.motion + t.sensor + t.normalize + t.resample + t.estimate;
  // Timer granularity can make the phases sum a hair past the total.
  const double other = t.total > phases ? t.total - phases : 0.0;
  return {t.motion, t.sensor, t.normalize, t.resample, t.estimate, other};
}

void write_histogram(JsonWriter& json, const DurationHistogram& h) {
  // Only the bins up to the last non-empty one: the tail of zeros says nothing.
  std::size_t used = 0;
  for (std::size_t k = 0; k < h.counts.size(); ++k) {
    if (h.counts[k] > 0) used = k + 1;
  }
  json.key("histogram").begin_object();
  json.key("upper_edge_ms").begin_array();
  for (std::size_t k = 0; k < used; ++k) json.value(DurationHistogram::upper_edge_ms(k));
  json.end_array();
  json.key("counts").begin_array();
  for (std::size_t k = 0; k < used; ++k) json.value(std::uint64_t{h.counts[k]});
  json.end_array();
  json.end_object();
}

}  // namespace

void DurationHistogram::add(double ms) noexcept {
  std::size_t k = 0;
  if (ms >= kFirstEdgeMs) {
    k = 1 + static_cast<std::size_t>(std::floor(std::log2(ms / kFirstEdgeMs)));
  }
  counts[k < kBins ? k : kBins - 1] += 1;  // NaN never reaches here: phase times are finite
}

double DurationHistogram::upper_edge_ms(std::size_t k) noexcept {
  if (k + 1 >= kBins) return std::numeric_limits<double>::infinity();
  return kFirstEdgeMs * std::ldexp(1.0, static_cast<int>(k));
}

RunProfile profile_run(const ReplayResult& result) {
  RunProfile profile;
  profile.phases.resize(kPhaseNames.size());
  std::array<std::vector<double>, kPhaseNames.size()> samples;
  double particles = 0.0;
  double particle_beams = 0.0;
  double total = 0.0;
  for (const UpdateRecord& u : result.updates) {
    const std::array<double, 6> t = phase_times(u.ms);
    for (std::size_t p = 0; p < t.size(); ++p) {
      samples[p].push_back(t[p]);
      profile.phases[p].histogram.add(t[p]);
      profile.phases[p].total_ms += t[p];
      total += t[p];
    }
    particles += static_cast<double>(u.particles);
    particle_beams += static_cast<double>(u.weighed) * static_cast<double>(u.beams);
  }
  for (std::size_t p = 0; p < kPhaseNames.size(); ++p) {
    PhaseProfile& phase = profile.phases[p];
    phase.name = kPhaseNames[p];
    phase.ms = summarize(std::move(samples[p]));
    phase.share = total > 0.0 ? phase.total_ms / total : 0.0;
    phase.ns_per_particle = particles > 0.0 ? phase.total_ms * 1e6 / particles : 0.0;
  }
  if (particle_beams > 0.0) {
    profile.ns_per_particle_beam = profile.phases[1].total_ms * 1e6 / particle_beams;
  }
  return profile;
}

void write_profile_json(JsonWriter& json, const RunProfile& profile) {
  json.key("profile").begin_object();
  json.member("ns_per_particle_beam", profile.ns_per_particle_beam);
  json.key("phases").begin_object();
  for (const PhaseProfile& p : profile.phases) {
    json.key(p.name).begin_object();
    json.member("mean_ms", p.ms.mean).member("p50_ms", p.ms.p50);
    json.member("p99_ms", p.ms.p99).member("max_ms", p.ms.max);
    json.member("total_ms", p.total_ms).member("share", p.share);
    json.member("ns_per_particle", p.ns_per_particle);
    write_histogram(json, p.histogram);
    json.end_object();
  }
  json.end_object();
  json.end_object();
}

void write_folded_stacks(std::ostream& out, const RunProfile& profile) {
  for (const PhaseProfile& p : profile.phases) {
    out << "mote;update;" << p.name << ' ' << std::llround(p.total_ms * 1000.0) << '\n';
  }
}

}  // namespace mote::replay
