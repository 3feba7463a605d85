// The `methods` argument of the module's functions: None, one name, a comma-separated list or a
// sequence of names, checked against the methods a function runs.
#pragma once
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace lsi::python {

// The names, in the order given, without repeats; empty for None (the scene's own methods).
// Raises ValueError for an unknown name or an empty list, TypeError for a value that is not a
// name or a sequence of names.
std::vector<std::string> method_names(pybind11::handle methods,
                                      const std::vector<std::string>& allowed);

}  // namespace lsi::python
