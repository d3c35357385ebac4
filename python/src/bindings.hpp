#pragma once
// Shared pieces of the `mote` Python module: one registration function per part of the API.

#include <pybind11/pybind11.h>

#include "mote/core/pose.hpp"

namespace mote::python {

namespace py = pybind11;

/// mote.Error, mote.InputError (also a ValueError), mote.ConfigError and their translation.
void bind_errors(py::module_& m);
/// Pose2, LaserScan, OccupancyGrid, load_map.
void bind_types(py::module_& m);
/// LocalizerConfig, its enums, load_config, nav2_defaults.
void bind_config(py::module_& m);
/// Localizer, its estimate, statistics and the zero-copy particle views.
void bind_localizer(py::module_& m);
/// open_log and replay.
void bind_replay(py::module_& m);

}  // namespace mote::python
