// How lsi's OpenMP threads wait between parallel regions, unless the user says otherwise:
// spin briefly, then sleep. Spinning without limit (libgomp's default) makes an MPM run on cores
// shared with other work many times slower; sleeping at once pays a wake-up at each of a step's
// parallel regions. The measurements: docs/notes/performance.md, "OpenMP threads between regions".
// On a dedicated machine GOMP_SPINCOUNT=1000 (or OMP_WAIT_POLICY=active) is faster still.
#pragma once
#include <cstdlib>

namespace lsi {

// Sets OMP_WAIT_POLICY=passive and GOMP_SPINCOUNT=300 (libgomp's spins before sleeping) when the
// user set no wait policy; a user's GOMP_SPINCOUNT is kept. Returns true when it changed the
// environment: the OpenMP runtime reads it when it loads, before main, so the caller must
// restart the program for it to take effect.
inline bool set_openmp_wait_defaults() {
  if (std::getenv("OMP_WAIT_POLICY") || setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return false;
  if (!std::getenv("GOMP_SPINCOUNT")) setenv("GOMP_SPINCOUNT", "300", 1);
  return true;
}

}  // namespace lsi
