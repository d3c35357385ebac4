// ParticleSet: zero-copy, read-only NumPy views of the particle columns (float32), whose base
// object is the ParticleSet, which holds the Localizer: a column outlives neither.
#include "particle_set.hpp"

#include <cstddef>
#include <string>

#include "mote/core/error.hpp"

namespace mote::python {
namespace {

constexpr std::array<const char*, 4> kColumns{"x", "y", "theta", "log_weight"};

const float* column_data(const ConstParticleView& v, std::size_t k) {
  const std::array<const float*, 4> columns{v.x, v.y, v.theta, v.logw};
  return columns[k];
}

void check_fresh(const ParticleSet& p) {
  const auto& l = p.owner.cast<const PyLocalizer&>();
  if (l.busy.load() || l.generation != p.generation) {
    throw Error(
        "stale particle view: the Localizer ran update() or initialize*() since these particles "
        "were taken; read Localizer.particles again, or keep particles.copy()");
  }
}

py::array read_only(py::array a) {
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::object column(const py::object& self, std::size_t k) {
  const auto& p = self.cast<const ParticleSet&>();
  if (p.owner.is_none()) return p.owned[k];
  check_fresh(p);
  const auto n = static_cast<py::ssize_t>(p.view.size());
  return read_only(
      py::array_t<float>({n}, {py::ssize_t{sizeof(float)}}, column_data(p.view, k), self));
}

ParticleSet copy_of(const py::object& self) {
  const auto& p = self.cast<const ParticleSet&>();
  ParticleSet c;
  c.owner = py::none();
  c.view.count = p.view.count;
  for (std::size_t k = 0; k < kColumns.size(); ++k) {
    const auto a = column(self, k).cast<py::array_t<float>>();
    c.owned[k] = py::array_t<float>(a.size(), a.data());  // owns a copy
  }
  return c;
}

}  // namespace

ParticleSet ParticleSet::view_of(const py::object& owner, const PyLocalizer& l) {
  ParticleSet p;
  p.owner = owner;
  p.generation = l.generation;
  p.view = l.impl.particles();
  return p;
}

void bind_particle_set(py::module_& m) {
  py::class_<ParticleSet> cls(
      m, "Particles",
      "The particle set. From Localizer.particles: x, y, theta (m, rad) and log_weight (natural "
      "log of the normalized weight) are float32 NumPy arrays viewing the C++ columns without a "
      "copy, read-only, valid until the next update() or initialize*() (reading a column after "
      "that raises mote.Error). copy() returns a set of owned, writeable arrays.");
  for (std::size_t k = 0; k < kColumns.size(); ++k) {
    cls.def_property_readonly(kColumns[k], [k](const py::object& self) { return column(self, k); });
  }
  cls.def("copy", &copy_of, "Owned copies of the four columns, which never go stale.")
      .def("__len__", [](const ParticleSet& p) { return p.view.size(); })
      .def_property_readonly(
          "is_view", [](const ParticleSet& p) { return !p.owner.is_none(); },
          "True for a view into the Localizer, False for a copy")
      .def_property_readonly(
          "valid",
          [](const ParticleSet& p) {
            if (p.owner.is_none()) return true;
            const auto& l = p.owner.cast<const PyLocalizer&>();
            return !l.busy.load() && l.generation == p.generation;
          },
          "False once the Localizer has moved on (a view's columns then raise)");
}

}  // namespace mote::python
