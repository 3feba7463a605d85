// The closed forms over NumPy arrays: the empirical and analytical models of a scene evaluated for
// arrays of its numeric fields in one call of the batched sweep kernel
// (sweeps/closed_form_sweep.hpp), checked as the scene parser checks a scene.
#pragma once
#include <pybind11/pybind11.h>

namespace lsi::python {

// Adds closed_forms(), empirical(), analytical() and closed_form_inputs to the module.
void add_closed_forms(pybind11::module_& m);

}  // namespace lsi::python
