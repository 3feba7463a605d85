#include "python/method_names.hpp"

#include <algorithm>
#include <sstream>

namespace py = pybind11;

namespace lsi::python {
namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> method_names(py::handle methods, const std::vector<std::string>& allowed) {
  if (methods.is_none()) return {};
  std::vector<std::string> given;
  if (py::isinstance<py::str>(methods)) {
    std::stringstream list(methods.cast<std::string>());
    for (std::string m; std::getline(list, m, ',');)
      if (!m.empty()) given.push_back(m);
  } else if (py::isinstance<py::sequence>(methods)) {
    for (const auto& m : methods) {
      if (!py::isinstance<py::str>(m))
        throw py::type_error("methods: " + std::string(py::repr(m)) +
                             ": a method is named by a string (allowed: " + joined(allowed) + ")");
      given.push_back(m.cast<std::string>());
    }
  } else {
    throw py::type_error("methods: " + std::string(py::repr(methods)) +
                         ": give a method's name or a list of them (allowed: " + joined(allowed) +
                         ")");
  }
  if (given.empty())
    throw py::value_error("methods: empty list (allowed: " + joined(allowed) + ")");
  std::vector<std::string> out;
  for (const auto& m : given) {
    if (std::find(allowed.begin(), allowed.end(), m) == allowed.end())
      throw py::value_error("methods: " + m + ": unknown method (allowed: " + joined(allowed) +
                            ")");
    if (std::find(out.begin(), out.end(), m) == out.end()) out.push_back(m);
  }
  return out;
}

}  // namespace lsi::python
