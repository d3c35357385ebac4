#pragma once
// The Localizer's state and the steps of one update (private to mote::engine).

#include <cstdint>
#include <memory>
#include <string>
#include <variant>

#include "mote/engine/beam_model.hpp"
#include "mote/engine/beams.hpp"
#include "mote/engine/executor.hpp"
#include "mote/engine/kld.hpp"
#include "mote/engine/likelihood_field_model.hpp"
#include "mote/engine/localizer.hpp"
#include "mote/engine/motion.hpp"
#include "mote/engine/particles.hpp"
#include "mote/engine/recovery.hpp"

namespace mote {

// Why the scan's geometry cannot be used (non-finite angles, NaN range limits or sensor pose),
// or empty when it can.
[[nodiscard]] std::string scan_geometry_problem(const LaserScan& scan);

using SensorVariant = std::variant<LikelihoodFieldModel, BeamModel>;
using MotionVariant = std::variant<OdometryModel, OmniModel, AckermannModel>;

struct Localizer::Impl {
  Impl(const OccupancyGrid& grid, LocalizerConfig cfg);

  // Steps of update(), in order (localizer_steps.cpp).
  bool reject(UpdateOutcome outcome, std::string reason);
  // Selects the beams; returns why they cannot be weighed, or empty when they can.
  [[nodiscard]] std::string select(const LaserScan& scan);
  [[nodiscard]] bool moved_enough(const Pose2& odometry) const;
  [[nodiscard]] bool jumped(const Pose2& odometry) const;
  bool reset_odometry(const Pose2& odometry);
  void predict(const Pose2& odometry);
  void weigh();
  void normalize();
  void maybe_resample();
  void update_estimate();

  // Initialization (localizer.cpp): forget everything but the map and the config.
  void start_fresh();

  LocalizerConfig config;
  OccupancyGrid map;
  Executor executor;
  MotionVariant motion;
  std::unique_ptr<SensorVariant> sensor;  // built inside the executor's arena
  BeamSelection selection;
  KldConfig kld;
  KldBins bins;
  AugmentedMcl recovery;
  PoseSummarizer summarize;  // keeps its scratch memory between updates
  ParticleStore store;
  BeamSet beams;
  LocalizationEstimate estimate;
  UpdateStats stats;

  std::uint64_t step = 0;  // filter updates run; keys the random streams
  bool initialized = false;
  bool has_odometry = false;
  bool degenerate = false;  // the last scan explained no particle
  Pose2 last_odometry;
  int updates_since_resample = 0;
};

}  // namespace mote
