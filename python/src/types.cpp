// Pose2, LaserScan and OccupancyGrid: poses convert from (x, y, theta) tuples, scans from NumPy
// ranges, and the grid's cells are a read-only NumPy view that keeps the grid alive.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>

#include "bindings.hpp"
#include "mote/core/scan.hpp"
#include "mote/maps/map_loader.hpp"
#include "mote/maps/occupancy_grid.hpp"

namespace mote::python {
namespace {

std::string pose_repr(const Pose2& p) {
  return "Pose2(x=" + std::to_string(p.x) + ", y=" + std::to_string(p.y) +
         ", theta=" + std::to_string(p.theta) + ")";
}

void bind_pose(py::module_& m) {
  py::class_<Pose2>(m, "Pose2", "A planar pose: x, y in metres, theta in radians.")
      .def(py::init<>())
      .def(py::init([](double x, double y, double theta) {
             return Pose2{x, y, theta};
           }),
           py::arg("x"), py::arg("y"), py::arg("theta"))
      .def(py::init([](const py::tuple& t) {
             if (t.size() != 3) throw py::value_error("a pose is (x, y, theta)");
             return Pose2{t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>()};
           }),
           py::arg("xytheta"), "From an (x, y, theta) tuple.")
      .def_readwrite("x", &Pose2::x, "m")
      .def_readwrite("y", &Pose2::y, "m")
      .def_readwrite("theta", &Pose2::theta, "rad")
      .def("__iter__", [](const Pose2& p) { return py::iter(py::make_tuple(p.x, p.y, p.theta)); })
      .def("__eq__", [](const Pose2& a, const Pose2& b) { return a == b; })
      .def("__repr__", &pose_repr);
  py::implicitly_convertible<py::tuple, Pose2>();
}

LaserScan make_scan(const py::array_t<float, py::array::c_style | py::array::forcecast>& ranges,
                    float angle_min, float angle_increment, float range_min, float range_max,
                    const Pose2& sensor_pose, double stamp) {
  if (ranges.ndim() != 1) throw py::value_error("ranges must be a 1-D array");
  LaserScan s;
  s.stamp = stamp;
  s.angle_min = angle_min;
  s.angle_increment = angle_increment;
  s.range_min = range_min;
  s.range_max = range_max;
  s.sensor_pose = sensor_pose;
  s.ranges.assign(ranges.data(), ranges.data() + ranges.size());
  return s;
}

void bind_scan(py::module_& m) {
  py::class_<LaserScan>(m, "LaserScan",
                        "One planar range scan (sensor_msgs/LaserScan semantics). Beam i points "
                        "at angle_min + i * angle_increment in the sensor frame; sensor_pose "
                        "places the sensor in the robot's base frame. Invalid readings (NaN, inf, "
                        "below range_min, at or above range_max) are dropped by the filter.")
      .def(py::init(&make_scan), py::arg("ranges"), py::arg("angle_min"),
           py::arg("angle_increment"), py::arg("range_min"), py::arg("range_max"),
           py::arg("sensor_pose") = Pose2{}, py::arg("stamp") = 0.0,
           "ranges: 1-D array of metres (copied, as float32).")
      .def_readwrite("stamp", &LaserScan::stamp, "s")
      .def_readwrite("angle_min", &LaserScan::angle_min, "rad")
      .def_readwrite("angle_increment", &LaserScan::angle_increment, "rad")
      .def_readwrite("range_min", &LaserScan::range_min, "m")
      .def_readwrite("range_max", &LaserScan::range_max, "m")
      .def_readwrite("sensor_pose", &LaserScan::sensor_pose, "mounting pose in the base frame")
      .def_property_readonly(
          "ranges",
          [](const LaserScan& s) { return py::array_t<float>(s.ranges.size(), s.ranges.data()); },
          "The ranges, m (a float32 copy).")
      .def("__len__", &LaserScan::size);
}

py::array cells_view(const py::object& self) {
  const auto& grid = self.cast<const OccupancyGrid&>();
  const auto* data = reinterpret_cast<const std::uint8_t*>(grid.cells().data());
  const auto width = static_cast<py::ssize_t>(grid.width());
  py::array_t<std::uint8_t> view({static_cast<py::ssize_t>(grid.height()), width},
                                 {width, py::ssize_t{1}}, data, self);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

void bind_grid(py::module_& m) {
  py::class_<OccupancyGrid>(m, "OccupancyGrid",
                            "An occupancy grid in the ROS map_server convention: cell (0, 0) is "
                            "the lower-left cell, its corner at `origin` in the map frame.")
      .def_property_readonly("width", &OccupancyGrid::width, "cells along x")
      .def_property_readonly("height", &OccupancyGrid::height, "cells along y")
      .def_property_readonly("resolution", &OccupancyGrid::resolution, "m per cell")
      .def_property_readonly("origin", &OccupancyGrid::origin, "pose of the lower-left corner")
      .def_property_readonly("free_cell_count", &OccupancyGrid::free_cell_count)
      .def_property_readonly("cells", &cells_view,
                             "Read-only uint8 view (height, width) of the cells, row 0 at the "
                             "bottom: 0 free, 1 occupied, 2 unknown. Keeps the grid alive.")
      .def(
          "world_to_cell",
          [](const OccupancyGrid& g, double x, double y) {
            const CellIndex c = g.world_to_cell({x, y});
            return std::pair{c.i, c.j};
          },
          py::arg("x"), py::arg("y"), "The cell (i column, j row) holding a map point (m).")
      .def(
          "cell_center",
          [](const OccupancyGrid& g, int i, int j) {
            const Point2 p = g.cell_center({i, j});
            return std::pair{p.x, p.y};
          },
          py::arg("i"), py::arg("j"), "Centre of a cell in the map frame (m).")
      .def(
          "contains",
          [](const OccupancyGrid& g, int i, int j) {
            return g.contains({i, j});
          },
          py::arg("i"), py::arg("j"));
}

}  // namespace

void bind_types(py::module_& m) {
  bind_pose(m);
  bind_scan(m);
  bind_grid(m);
  m.def(
      "load_map",
      [](const std::string& path) {
        const py::gil_scoped_release unlocked;
        return load_map(path);
      },
      py::arg("path"), "Loads a map_server map (YAML and its PGM/PNG image). Raises InputError.");
}

}  // namespace mote::python
