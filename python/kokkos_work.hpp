// Work on Kokkos from Python: started once (model/mpm_runner.hpp, ensure_kokkos), one call at a
// time (Python threads may call the module together; the driver and Kokkos' default execution
// space instance serve one caller at a time), and without Python's lock meanwhile, so that other
// Python threads run.
#pragma once
#include <pybind11/pybind11.h>

#include <mutex>

#include "model/mpm_runner.hpp"

namespace lsi::python {

inline std::mutex& kokkos_mutex() {
  static std::mutex m;
  return m;
}

// Runs f() with Kokkos started, under kokkos_mutex, without the GIL; returns what f returns.
template <class F>
auto with_kokkos(F&& f) {
  pybind11::gil_scoped_release release;
  const std::lock_guard<std::mutex> lock(kokkos_mutex());
  ensure_kokkos();
  return f();
}

}  // namespace lsi::python
