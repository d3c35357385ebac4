// The readers and the replay loop: mote.open_log iterates (stamp, odometry, scan) over any log
// `mote replay` reads, mote.replay runs `mote replay` and returns its report.json as a dict.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/logs/scan_source.hpp"
#include "mote/replay/replay_run.hpp"
#include "mote/replay/report.hpp"

namespace mote::python {
namespace {

/// A log being read; next() runs without the GIL.
class LogReader {
 public:
  explicit LogReader(std::unique_ptr<logs::ScanSource> source) : source_(std::move(source)) {}

  py::tuple next() {
    if (busy_.exchange(true)) throw Error("LogReader: already in use by another thread");
    std::optional<logs::ScanFrame> frame;
    try {
      const py::gil_scoped_release unlocked;
      frame = source_->next();
    } catch (...) {
      busy_.store(false);
      throw;
    }
    busy_.store(false);
    if (!frame) throw py::stop_iteration();
    return py::make_tuple(frame->stamp, frame->odometry, std::move(frame->scan));
  }
  [[nodiscard]] py::dict stats() const {
    const logs::ReadStats s = source_->stats();
    py::dict d;
    d["records_read"] = s.records_read;
    d["records_ignored"] = s.records_ignored;
    d["records_skipped"] = s.records_skipped;
    d["bytes_skipped"] = s.bytes_skipped;
    d["first_error"] = s.first_error;
    d["warnings"] = s.warnings;
    return d;
  }
  [[nodiscard]] std::string range_max_source() const { return source_->range_max_source(); }

 private:
  std::unique_ptr<logs::ScanSource> source_;
  std::atomic<bool> busy_{false};  ///< next() runs without the GIL: one thread at a time
};

logs::ReaderOptions reader_options(bool lenient, std::optional<float> laser_max_range,
                                   const std::string& scan_topic, const std::string& odom_topic,
                                   const std::string& odom_frame, const std::string& base_frame) {
  logs::ReaderOptions o;
  o.lenient = lenient;
  o.carmen_max_range = laser_max_range;
  o.scan_topic = scan_topic;
  o.odom_topic = odom_topic;
  o.odom_frame = odom_frame;
  o.base_frame = base_frame;
  return o;
}

/// (stamp, x, y, theta) rows: the best-cluster mean after every update that ran.
py::array_t<double> trajectory_array(const std::vector<logs::StampedPose>& poses) {
  py::array_t<double> a({static_cast<py::ssize_t>(poses.size()), py::ssize_t{4}});
  auto rows = a.mutable_unchecked<2>();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const auto r = static_cast<py::ssize_t>(k);
    rows(r, 0) = poses[k].stamp;
    rows(r, 1) = poses[k].pose.x;
    rows(r, 2) = poses[k].pose.y;
    rows(r, 3) = poses[k].pose.theta;
  }
  return a;
}

/// `config` as `mote replay --config` reads it (a path) or a LocalizerConfig; None = defaults.
LocalizerConfig config_of(const py::object& config) {
  if (config.is_none()) return {};
  if (py::isinstance<LocalizerConfig>(config)) return config.cast<LocalizerConfig>();
  return py::module_::import("mote").attr("load_config")(config).cast<LocalizerConfig>();
}

py::dict replay_to_dict(const std::filesystem::path& map, const std::filesystem::path& log,
                        const std::optional<std::filesystem::path>& reference,
                        const py::object& config, std::optional<int> particles, std::uint64_t seed,
                        int threads, const std::optional<std::filesystem::path>& out, bool lenient,
                        std::optional<float> laser_max_range,
                        const std::optional<Pose2>& init_pose) {
  replay::ReplayOptions o;
  o.map = map;
  o.log = log;
  if (reference) o.reference = *reference;
  o.config = config_of(config);
  if (particles) o.config.min_particles = o.config.max_particles = *particles;
  o.config.seed = seed;
  o.config.threads = threads;
  o.reader.lenient = lenient;
  if (laser_max_range) {  // as mote replay --laser-max-range
    o.reader.carmen_max_range = laser_max_range;
    o.config.laser_max_range = *laser_max_range;
  }
  if (init_pose) {  // as mote replay --init-pose
    o.init = replay::InitMode::kPose;
    o.init_pose = *init_pose;
  }
  std::string json;
  std::vector<logs::StampedPose> trajectory;
  {
    const py::gil_scoped_release unlocked;
    const replay::ReplayResult result = replay::run_replay(o);
    if (out) replay::write_replay_outputs(*out, result);
    std::ostringstream text;
    replay::write_report_json(text, result);
    json = text.str();
    trajectory = result.trajectory;
  }
  auto report = py::module_::import("json").attr("loads")(json).cast<py::dict>();
  report["trajectory"] = trajectory_array(trajectory);
  return report;
}

}  // namespace

void bind_replay(py::module_& m) {
  py::class_<LogReader>(m, "LogReader", "Frames of a recorded log, in recording order.")
      .def("__iter__", [](const py::object& self) { return self; })
      .def("__next__", &LogReader::next, "(stamp s, odometry Pose2, LaserScan); GIL released")
      .def_property_readonly("stats", &LogReader::stats, "what the reader consumed so far")
      .def_property_readonly("range_max_source", &LogReader::range_max_source);
  m.def(
      "open_log",
      [](const std::filesystem::path& path, bool lenient, std::optional<float> laser_max_range,
         const std::string& scan_topic, const std::string& odom_topic,
         const std::string& odom_frame, const std::string& base_frame) {
        const logs::ReaderOptions o = reader_options(lenient, laser_max_range, scan_topic,
                                                     odom_topic, odom_frame, base_frame);
        const py::gil_scoped_release unlocked;
        return std::make_unique<LogReader>(logs::open_scan_log(path, o));
      },
      py::arg("path"), py::kw_only(), py::arg("lenient") = false,
      py::arg("laser_max_range") = py::none(), py::arg("scan_topic") = "",
      py::arg("odom_topic") = "", py::arg("odom_frame") = "odom", py::arg("base_frame") = "",
      "Opens a recorded log by its extension (CARMEN .clf/.log, ROS 1 .bag, ROS 2 rosbag2 folder, "
      ".mcap, .db3) and iterates (stamp, odometry, scan). Options as mote replay's flags. Raises "
      "InputError naming the file.");
  m.def("replay", &replay_to_dict, py::kw_only(), py::arg("map"), py::arg("log"),
        py::arg("reference") = py::none(), py::arg("config") = py::none(),
        py::arg("particles") = py::none(), py::arg("seed") = 42, py::arg("threads") = 0,
        py::arg("out") = py::none(), py::arg("lenient") = false,
        py::arg("laser_max_range") = py::none(), py::arg("init_pose") = py::none(),
        "Runs a log through the filter as `mote replay` does (GIL released) and returns "
        "report.json as a dict. config: a LocalizerConfig or a YAML path; particles fixes "
        "min = max; seed and threads replace the config's; init_pose starts there (0.1 m, 5 deg) "
        "instead of at the reference's first pose (or global). The dict adds 'trajectory', an "
        "(N, 4) array of stamp, x, y, theta after every update. With out, writes report.json, "
        "trajectory.tum, updates.csv and map.png there.");
}

}  // namespace mote::python
