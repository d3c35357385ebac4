// mote.Localizer: the C++ Localizer with the GIL released while it works, plus a generation
// counter so that particle views from before the last update() or initialize*() refuse to be
// read instead of showing whatever the buffers hold now.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdint>
#include <utility>

#include "bindings.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/localizer.hpp"
#include "particle_set.hpp"

namespace mote::python {
namespace {

/// Marks the Localizer busy for one call: mote's Localizer must not be used from two threads at
/// once, and with the GIL released Python threads could try.
class BusyGuard {
 public:
  explicit BusyGuard(PyLocalizer& l) : busy_(l.busy) {
    if (busy_.exchange(true)) throw Error("Localizer: already in use by another thread");
  }
  ~BusyGuard() { busy_.store(false); }
  BusyGuard(const BusyGuard&) = delete;
  BusyGuard& operator=(const BusyGuard&) = delete;

 private:
  std::atomic<bool>& busy_;
};

/// Runs `work` on the Localizer without the GIL; particle views taken before are stale after.
template <typename Work>
auto run_unlocked(PyLocalizer& l, Work&& work) {
  const BusyGuard guard(l);
  ++l.generation;
  const py::gil_scoped_release unlocked;
  return work(l.impl);
}

void bind_stats(py::module_& m) {
  py::enum_<UpdateOutcome>(m, "UpdateOutcome", "Why update() did or did not run the filter.")
      .value("UPDATED", UpdateOutcome::kUpdated)
      .value("INITIALIZED", UpdateOutcome::kInitialized)
      .value("NOT_MOVED", UpdateOutcome::kNotMoved)
      .value("REJECTED_ODOMETRY", UpdateOutcome::kRejectedOdometry)
      .value("REJECTED_SCAN", UpdateOutcome::kRejectedScan)
      .value("UNEXPLAINED_SCAN", UpdateOutcome::kUnexplainedScan);
  py::enum_<LocalizationState>(m, "LocalizationState",
                               "Whether the filter knows where the robot is.")
      .value("TRACKING", LocalizationState::kTracking)
      .value("UNCERTAIN", LocalizationState::kUncertain)
      .value("LOST", LocalizationState::kLost);
  py::class_<PhaseTimes>(m, "PhaseTimes", "Wall-clock milliseconds of each phase of an update.")
      .def_readonly("motion", &PhaseTimes::motion)
      .def_readonly("sensor", &PhaseTimes::sensor)
      .def_readonly("normalize", &PhaseTimes::normalize)
      .def_readonly("resample", &PhaseTimes::resample)
      .def_readonly("estimate", &PhaseTimes::estimate)
      .def_readonly("total", &PhaseTimes::total);
  py::class_<OdometryAlphas>(m, "OdometryAlphas", "Odometry noise (Thrun table 5.6).")
      .def_readonly("alpha1", &OdometryAlphas::alpha1)
      .def_readonly("alpha2", &OdometryAlphas::alpha2)
      .def_readonly("alpha3", &OdometryAlphas::alpha3)
      .def_readonly("alpha4", &OdometryAlphas::alpha4);
  py::class_<UpdateStats>(m, "UpdateStats", "Statistics of the last call to update().")
      .def_readonly("outcome", &UpdateStats::outcome)
      .def_readonly("reason", &UpdateStats::reason, "one line, for unusual outcomes")
      .def_readonly("step", &UpdateStats::step, "filter updates run so far")
      .def_readonly("particles", &UpdateStats::particles, "after the update")
      .def_readonly("weighed", &UpdateStats::weighed, "particles the scan weighed")
      .def_readonly("beams", &UpdateStats::beams, "beams weighed")
      .def_readonly("blocked_beams", &UpdateStats::blocked_beams,
                    "beams left out as blocked by unmapped obstacles")
      .def_readonly("effective_sample_size", &UpdateStats::effective_sample_size)
      .def_readonly("resampled", &UpdateStats::resampled)
      .def_readonly("injected", &UpdateStats::injected, "augmented MCL's particles (amcl's rule)")
      .def_readonly("relocalized", &UpdateStats::relocalized,
                    "particles a re-localization added before this update")
      .def_readonly("state", &UpdateStats::state, "tracking, uncertain or lost")
      .def_readonly("hit_share", &UpdateStats::hit_share,
                    "share of readings ending within sigma_hit of a surface (refined pose)")
      .def_readonly("see_through", &UpdateStats::see_through,
                    "share of beams seeing through a mapped obstacle (refined pose)")
      .def_readonly("misfit", &UpdateStats::misfit, "the smoothed misfit the state comes from")
      .def_readonly("lost_bound", &UpdateStats::lost_bound,
                    "the misfit above which the state is lost (lost_misfit, or what the map "
                    "and laser learned while tracking)")
      .def_readonly("tempering", &UpdateStats::tempering, "likelihood exponent tau")
      .def_readonly("tempering_trials", &UpdateStats::tempering_trials)
      .def_readonly("log_evidence", &UpdateStats::log_evidence)
      .def_readonly("alphas", &UpdateStats::alphas)
      .def_readonly("log_w_slow", &UpdateStats::log_w_slow)
      .def_readonly("log_w_fast", &UpdateStats::log_w_fast)
      .def_readonly("ms", &UpdateStats::ms, "phase times, ms")
      .def_property_readonly("ran", &UpdateStats::ran, "True when the filter ran");
}

void bind_estimate(py::module_& m) {
  py::class_<ScanMatch>(m, "ScanMatch", "The best hypothesis matched to the map.")
      .def_readonly("pose", &ScanMatch::pose, "refined pose (map frame)")
      .def_readonly("covariance", &ScanMatch::covariance, "3x3 over (x, y, theta), Laplace")
      .def_readonly("endpoints", &ScanMatch::endpoints, "readings matched")
      .def_readonly("hit_share", &ScanMatch::hit_share)
      .def_readonly("iterations", &ScanMatch::iterations);
  py::class_<PoseEstimate>(m, "PoseEstimate", "A weighted Gaussian summary of particles.")
      .def_readonly("mean", &PoseEstimate::mean, "weighted mean (circular for theta)")
      .def_readonly("covariance", &PoseEstimate::covariance, "3x3 over (x, y, theta)")
      .def_readonly("weight", &PoseEstimate::weight, "total normalized weight")
      .def_readonly("count", &PoseEstimate::count, "particles");
  py::class_<LocalizationEstimate>(m, "LocalizationEstimate",
                                   "The whole set and its clusters, heaviest first.")
      .def_readonly("overall", &LocalizationEstimate::overall)
      .def_readonly("clusters", &LocalizationEstimate::clusters)
      .def_readonly("refined", &LocalizationEstimate::refined,
                    "the heaviest cluster's mean matched to the map with every reading")
      .def_property_readonly("best", &LocalizationEstimate::best, "the heaviest cluster")
      .def_property_readonly("mean", [](const LocalizationEstimate& e) { return e.overall.mean; })
      .def_property_readonly("covariance",
                             [](const LocalizationEstimate& e) { return e.overall.covariance; });
}

/// The Localizer for a read between calls: reading while another thread updates it is refused.
const Localizer& idle(const PyLocalizer& l) {
  if (l.busy.load()) throw Error("Localizer: read during an update in another thread");
  return l.impl;
}

void bind_localizer_class(py::module_& m) {
  py::class_<PyLocalizer>(m, "Localizer",
                          "Monte Carlo localization on a fixed occupancy grid. Construct with a "
                          "map and a LocalizerConfig, initialize, then update() with every "
                          "odometry pose and scan. One Localizer serves one thread at a time.")
      .def(py::init([](const OccupancyGrid& map, const LocalizerConfig& config) {
             const py::gil_scoped_release unlocked;
             return std::make_unique<PyLocalizer>(map, config);
           }),
           py::arg("map"), py::arg("config") = LocalizerConfig{},
           "Validates the config (ConfigError) and builds the sensor model's tables.")
      .def(
          "initialize",
          [](PyLocalizer& l, const Pose2& mean, const Eigen::Matrix3d& covariance) {
            run_unlocked(l, [&](Localizer& loc) { loc.initialize(mean, covariance); });
          },
          py::arg("pose"), py::arg("cov"),
          "Draws particles from N(pose, cov); cov is 3x3 over (x m, y m, theta rad).")
      .def(
          "initialize_global",
          [](PyLocalizer& l) { run_unlocked(l, [](Localizer& loc) { loc.initialize_global(); }); },
          "Draws particles uniformly over the map's free space (global localization).")
      .def(
          "update",
          [](PyLocalizer& l, const Pose2& odometry, const LaserScan& scan) {
            return run_unlocked(l, [&](Localizer& loc) { return loc.update(odometry, scan); });
          },
          py::arg("odometry"), py::arg("scan"),
          "One filter step (GIL released). Returns True when the filter ran; see last_update. "
          "Particle views taken before become stale.")
      .def_property_readonly(
          "estimate", [](const PyLocalizer& l) { return idle(l).estimate(); },
          "A copy of the current estimate (mean, covariance, clusters).")
      .def_property_readonly(
          "last_update", [](const PyLocalizer& l) { return idle(l).last_update(); },
          "A copy of the statistics of the last update().")
      .def_property_readonly(
          "config", [](const PyLocalizer& l) { return l.impl.config(); }, "a copy")
      .def_property_readonly("threads", [](const PyLocalizer& l) { return l.impl.threads(); })
      .def_property_readonly(
          "particles",
          [](const py::object& self) {
            const auto& l = self.cast<const PyLocalizer&>();
            idle(l);
            return ParticleSet::view_of(self, l);
          },
          "The particles as zero-copy read-only NumPy views (x, y, theta, log_weight), valid "
          "until the next update() or initialize*(); copy() keeps them.");
}

}  // namespace

void bind_localizer(py::module_& m) {
  bind_stats(m);
  bind_estimate(m);
  bind_particle_set(m);
  bind_localizer_class(m);
}

}  // namespace mote::python
