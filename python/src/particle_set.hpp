#pragma once
// The particle columns as NumPy arrays: views into the Localizer's buffers that check, on every
// read, that no update() or initialize*() has run since they were taken (those may resample into
// the other buffer), or owned copies that never go stale.

#include <pybind11/numpy.h>

#include <array>
#include <atomic>
#include <cstdint>

#include "bindings.hpp"
#include "mote/engine/localizer.hpp"

namespace mote::python {

/// The Localizer as Python holds it: with the generation its particle views are checked against.
struct PyLocalizer {
  PyLocalizer(const OccupancyGrid& map, const LocalizerConfig& config) : impl(map, config) {}
  Localizer impl;
  std::uint64_t generation = 0;  ///< bumped by every call that may move the particles
  std::atomic<bool> busy{false};
};

/// Either a view (owner set: the Localizer, kept alive) or a copy (arrays owned).
struct ParticleSet {
  py::object owner;  ///< the Localizer's Python object; None for a copy
  std::uint64_t generation = 0;
  ConstParticleView view;
  std::array<py::object, 4> owned;  ///< a copy's arrays: x, y, theta, log_weight

  [[nodiscard]] static ParticleSet view_of(const py::object& owner, const PyLocalizer& l);
};

void bind_particle_set(py::module_& m);

}  // namespace mote::python
