// `import mote`: pybind11 bindings over mote's public API (design.md section 1, python/).
#include "bindings.hpp"

PYBIND11_MODULE(_mote, m) {
  m.doc() =
      "mote: Monte Carlo localization on 2D occupancy grids, at C++ speed.\n"
      "Units are SI (m, rad, s); angles are wrapped to (-pi, pi].";
  mote::python::bind_errors(m);
  mote::python::bind_types(m);
  mote::python::bind_config(m);
  mote::python::bind_localizer(m);
  mote::python::bind_replay(m);
}
