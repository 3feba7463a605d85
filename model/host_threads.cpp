#include "model/host_threads.hpp"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <thread>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace lsi {

std::size_t host_thread_count() {
#if defined(_OPENMP)
  return static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
#else
  if (const char* env = std::getenv("OMP_NUM_THREADS")) {
    const long k = std::strtol(env, nullptr, 10);
    if (k > 0) return static_cast<std::size_t>(k);
  }
  return std::max(1u, std::thread::hardware_concurrency());
#endif
}

void on_host_threads(std::size_t n, const std::function<void(std::size_t)>& worker) {
  n = std::max<std::size_t>(n, 1);
  std::vector<std::exception_ptr> errors(n);
  auto guarded = [&](std::size_t t) {
    try {
      worker(t);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  if (n == 1) {
    guarded(0);
  } else {
#if defined(_OPENMP)
    const int team = static_cast<int>(n);
#pragma omp parallel num_threads(team)
    { guarded(static_cast<std::size_t>(omp_get_thread_num())); }
#else
    std::vector<std::thread> pool;
    try {
      for (std::size_t t = 1; t < n; ++t) pool.emplace_back(guarded, t);
    } catch (...) {  // no more threads: those started and this one share the work
    }
    guarded(0);
    for (auto& th : pool) th.join();
#endif
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace lsi
