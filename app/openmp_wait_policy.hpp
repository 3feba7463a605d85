// How lsi's OpenMP threads wait between parallel regions, unless the user says otherwise:
// spin briefly, then sleep. Spinning without limit (libgomp's default) makes an MPM run on cores
// shared with other work many times slower; sleeping at once pays a wake-up at each of a step's
// parallel regions. The measurements: docs/notes/performance.md, "OpenMP threads between regions".
// On a dedicated machine GOMP_SPINCOUNT=1000 (or OMP_WAIT_POLICY=active) is faster still.
#pragma once
#include <cstdlib>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#include <unistd.h>
#endif
#if defined(_OPENMP)
#include <omp.h>
#endif

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

#if defined(__linux__)
// Restarts the program (execv of `path` with `argv`), in the environment as it is now. With a
// binding (OMP_PROC_BIND, OMP_PLACES) the OpenMP runtime binds the program's first thread to the
// first place when it loads, and a program started by execv inherits that binding: its runtime
// would make its places of that one CPU and run every thread there. So the thread first gets
// back every CPU of the places (made from the CPUs the program was started with). Returns only
// when execv fails, with the binding as it was.
inline void restart_program(const char* path, char** argv) {
#if defined(_OPENMP)
  cpu_set_t bound;
  const bool known = sched_getaffinity(0, sizeof bound, &bound) == 0;
  if (known) {
    cpu_set_t all = bound;
    for (int p = 0; p < omp_get_num_places(); ++p) {
      std::vector<int> ids(static_cast<std::size_t>(omp_get_place_num_procs(p)));
      omp_get_place_proc_ids(p, ids.data());
      for (const int id : ids)
        if (id >= 0 && id < CPU_SETSIZE) CPU_SET(id, &all);
    }
    (void)sched_setaffinity(0, sizeof all, &all);
  }
#endif
  execv(path, argv);
#if defined(_OPENMP)
  if (known) (void)sched_setaffinity(0, sizeof bound, &bound);
#endif
}
#endif

}  // namespace lsi
