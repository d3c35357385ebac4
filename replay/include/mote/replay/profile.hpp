#pragma once
/// \file
/// `mote replay --profile`: where each update's time went. Per phase, the distribution of its
/// wall-clock time over the run (percentiles and a log-spaced histogram) and its cost per
/// particle; and the run as folded stacks ("mote;update;sensor 1234", microseconds), the input
/// format of flamegraph.pl, inferno and speedscope.

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string_view>
#include <vector>

#include "mote/replay/metrics.hpp"
#include "mote/replay/replay_run.hpp"

namespace mote::replay {

class JsonWriter;

/// Durations in log-spaced bins: bin 0 counts values below first_edge_ms, bin k >= 1 counts
/// [first_edge_ms * 2^(k-1), first_edge_ms * 2^k), the last bin everything above.
struct DurationHistogram {
  static constexpr double kFirstEdgeMs = 0.001;  ///< 1 microsecond
  static constexpr std::size_t kBins = 26;       ///< up to about 16 s, then the overflow bin

  std::array<std::uint64_t, kBins> counts{};

  void add(double ms) noexcept;
  /// Upper edge of bin k, ms (infinity for the last bin).
  [[nodiscard]] static double upper_edge_ms(std::size_t k) noexcept;
};

/// One phase of the update over a whole run.
struct PhaseProfile {
  std::string_view name;  ///< motion, sensor, normalize, resample, estimate, other
  Percentiles ms;         ///< per-update wall-clock time
  double total_ms = 0.0;  ///< summed over the run
  double share = 0.0;     ///< fraction of the summed update time
  double ns_per_particle = 0.0;
  DurationHistogram histogram;
};

/// The profile of a run: the five phases of Localizer::update plus "other" (gate, beam
/// selection and bookkeeping: total minus the phases).
struct RunProfile {
  std::vector<PhaseProfile> phases;
  /// Sensor-phase nanoseconds per particle-beam likelihood.
  double ns_per_particle_beam = 0.0;
};

/// The profile of a run's update records.
[[nodiscard]] RunProfile profile_run(const ReplayResult& result);

/// Writes `"profile": {...}` as a member of the current JSON object.
void write_profile_json(JsonWriter& json, const RunProfile& profile);

/// Writes one line per phase, "mote;update;PHASE MICROSECONDS", summed over the run.
void write_folded_stacks(std::ostream& out, const RunProfile& profile);

}  // namespace mote::replay
