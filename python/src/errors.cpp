// mote's exceptions as Python exceptions: the same one-line messages, InputError also a
// ValueError so code that catches ValueError for bad input keeps working.
#include <exception>

#include "bindings.hpp"
#include "mote/core/error.hpp"

namespace mote::python {
namespace {

PyObject* new_exception(const char* name, PyObject* bases, const char* doc) {
  PyObject* type = PyErr_NewExceptionWithDoc(name, doc, bases, nullptr);
  if (type == nullptr) throw py::error_already_set();
  return type;
}

}  // namespace

void bind_errors(py::module_& m) {
  // Module-lifetime references: the translator below outlives any one call.
  static PyObject* error =
      new_exception("mote.Error", PyExc_RuntimeError, "Base of every exception mote raises.");
  const py::tuple input_bases = py::make_tuple(py::handle(error), py::handle(PyExc_ValueError));
  static PyObject* input_error =
      new_exception("mote.InputError", input_bases.ptr(),
                    "Malformed or unreadable input; the message reads 'FILE: PLACE: PROBLEM'.");
  static PyObject* config_error = new_exception(
      "mote.ConfigError", error, "A configuration value out of range, or an API misuse.");
  m.add_object("Error", py::handle(error));
  m.add_object("InputError", py::handle(input_error));
  m.add_object("ConfigError", py::handle(config_error));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error, e.what());
    } catch (const ConfigError& e) {
      PyErr_SetString(config_error, e.what());
    } catch (const Error& e) {
      PyErr_SetString(error, e.what());
    }
  });
}

}  // namespace mote::python
