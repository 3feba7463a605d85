// How lsi's OpenMP threads wait between parallel regions, unless the user says otherwise:
// spin briefly, then sleep. Spinning without limit (libgomp's default) makes an MPM run on cores
// shared with other work many times slower; sleeping at once pays a wake-up at each of a step's
// parallel regions. The measurements: docs/notes/performance.md, "OpenMP threads between regions".
// On a dedicated machine GOMP_SPINCOUNT=1000 (or OMP_WAIT_POLICY=active) is faster still.
#pragma once
#include <cstdlib>
#include <cstring>
#include <string>
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
// back every CPU of the places (which the runtime made within the CPUs the program was started
// with), and where OMP_NUM_THREADS is not set it is set to the runtime's thread count, which
// the restarted runtime would otherwise take from the CPUs of the places alone. Returns only
// when execv fails, with the binding as it was.
inline void restart_program(const char* path, char** argv) {
#if defined(_OPENMP)
  // CPU sets sized for every CPU the system may have (more than CPU_SETSIZE on large machines).
  int cpus = CPU_SETSIZE;
  const long configured = sysconf(_SC_NPROCESSORS_CONF);
  if (configured > cpus) cpus = static_cast<int>(configured);
  std::vector<std::vector<int>> places(static_cast<std::size_t>(omp_get_num_places()));
  for (std::size_t p = 0; p < places.size(); ++p) {
    places[p].resize(static_cast<std::size_t>(omp_get_place_num_procs(static_cast<int>(p))));
    omp_get_place_proc_ids(static_cast<int>(p), places[p].data());
    for (const int id : places[p])
      if (id >= cpus) cpus = id + 1;
  }
  const std::size_t bytes = CPU_ALLOC_SIZE(cpus);
  cpu_set_t* const bound = CPU_ALLOC(cpus);
  cpu_set_t* const all = CPU_ALLOC(cpus);
  const bool known = bound && all && sched_getaffinity(0, bytes, bound) == 0;
  if (known && !places.empty()) {
    std::memcpy(all, bound, bytes);
    for (const auto& ids : places)
      for (const int id : ids)
        if (id >= 0) CPU_SET_S(static_cast<std::size_t>(id), bytes, all);
    if (!std::getenv("OMP_NUM_THREADS"))
      setenv("OMP_NUM_THREADS", std::to_string(omp_get_max_threads()).c_str(), 1);
    (void)sched_setaffinity(0, bytes, all);
  }
#endif
  execv(path, argv);
#if defined(_OPENMP)
  if (known && !places.empty()) (void)sched_setaffinity(0, bytes, bound);
  if (bound) CPU_FREE(bound);
  if (all) CPU_FREE(all);
#endif
}
#endif

}  // namespace lsi
