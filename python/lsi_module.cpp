// The Python module `lsi` (docs/guide/python.md): the closed forms over NumPy arrays
// (closed_forms.cpp) and a scene run through the driver (run_scene.cpp).
#include <pybind11/pybind11.h>

#include <exception>

#include "model/input_error.hpp"
#include "python/closed_forms.hpp"
#include "python/run_scene.hpp"

namespace py = pybind11;

PYBIND11_MODULE(lsi, m) {
  m.doc() =
      "lsi: landslide-structure interaction. closed_forms(), empirical(), analytical(): the\n"
      "closed-form design methods over NumPy arrays of scene fields; run(): a scene through the\n"
      "empirical, analytical, literature and MPM methods, as `lsi run`. SI units; forces and\n"
      "masses per metre of barrier width.";
  m.attr("__version__") = LSI_VERSION;
  // Each docstring starts with its signature, in Python's words.
  py::options options;
  options.disable_function_signatures();
  // Bad input (lsi::InputError, one line naming the field, its value and what is allowed) is a
  // ValueError.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const lsi::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  lsi::python::add_closed_forms(m);
  lsi::python::add_run(m);
}
