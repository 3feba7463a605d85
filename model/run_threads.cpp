#include "model/run_threads.hpp"

#include "kernels/common/execution_instance.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <exception>
#include <type_traits>

#if defined(KOKKOS_ENABLE_OPENMP)
#include <omp.h>
#endif

namespace lsi {
namespace {

long g_points_per_thread = -1;  // < 0: the defaults

// A partition helps where the MPM's kernels run on the OpenMP threads: the default space is the
// host's OpenMP space and Kokkos 3 has partitions.
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
constexpr bool kPartitions = std::is_same_v<Kokkos::DefaultExecutionSpace, Kokkos::OpenMP>;
#else
constexpr bool kPartitions = false;
#endif

}  // namespace

void set_points_per_thread(long points) { g_points_per_thread = std::max(0L, points); }
void reset_points_per_thread() { g_points_per_thread = -1; }
long points_per_thread(bool saturated) {
  if (g_points_per_thread >= 0) return g_points_per_thread;
  return saturated ? kDefaultPointsPerThreadSaturated : kDefaultPointsPerThreadDry;
}

int threads_for_run(long points, bool saturated) {
  const int threads = instance_concurrency<Kokkos::DefaultExecutionSpace>();
  const long per_thread = points_per_thread(saturated);
  if (per_thread <= 0) return threads;
  const long wanted = std::max(1L, points / per_thread);
  return static_cast<int>(std::min<long>(wanted, threads));
}

void run_on_threads(int threads, const std::function<void()>& f) {
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
  if constexpr (kPartitions) {
    // Inside a parallel region (a campaign's partition) the run keeps the threads it was given.
    if (threads >= 1 && threads < instance_concurrency<Kokkos::OpenMP>() && omp_get_level() == 0) {
      const int levels = omp_get_max_active_levels();
      omp_set_max_active_levels(std::max(levels, 2));
      std::exception_ptr error;
      Kokkos::OpenMP::partition_master(
          [&](int, int) {
            try {
              f();
            } catch (...) {
              error = std::current_exception();
            }
          },
          1, threads);
      omp_set_max_active_levels(levels);
      if (error) std::rethrow_exception(error);
      return;
    }
  }
#endif
  (void)threads;
  f();
}

}  // namespace lsi
