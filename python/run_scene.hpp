// run(): a scene through the driver, as `lsi run` runs it (the closed forms the scene selects,
// then the MPM), its results as Python dicts of floats and NumPy arrays, with the MPM's snapshots
// of the material points where the scene asks for them.
#pragma once
#include <pybind11/pybind11.h>

namespace lsi::python {

// Adds run() to the module.
void add_run(pybind11::module_& m);

}  // namespace lsi::python
