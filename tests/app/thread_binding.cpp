// Prints the CPUs each thread of host work may run on (model/host_threads.hpp), one line per
// thread, "t: cpu cpu ...", after the restart that lsi's main does to set its OpenMP wait
// defaults (app/openmp_wait_policy.hpp). thread_binding_test.sh runs it under several bindings.
#include <sched.h>

#include <cstdio>
#include <string>
#include <vector>

#include "app/openmp_wait_policy.hpp"
#include "model/host_threads.hpp"

int main(int, char** argv) {
  if (lsi::set_openmp_wait_defaults()) lsi::restart_program("/proc/self/exe", argv);
  const std::size_t n = lsi::host_thread_count();
  std::vector<std::string> cpus(n);
  lsi::on_host_threads(n, [&](std::size_t t) {
    cpu_set_t set;
    std::string line;
    if (sched_getaffinity(0, sizeof set, &set) == 0)
      for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &set)) line += " " + std::to_string(c);
    cpus[t] = line;  // each thread its own entry
  });
  for (std::size_t t = 0; t < n; ++t) std::printf("%zu:%s\n", t, cpus[t].c_str());
  return 0;
}
