#include "model/run_threads.hpp"

#include "kernels/common/execution_instance.hpp"
#include "model/host_threads.hpp"

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

bool runs_on_one_thread(long points, bool saturated) {
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
  if constexpr (kPartitions) {
    const long per_thread = points_per_thread(saturated);
    // Inside a parallel region (a campaign's partition) the run keeps the threads it was given.
    // Before Kokkos starts (a footprint's estimate), the threads it will take.
    const std::size_t threads =
        Kokkos::is_initialized() ? static_cast<std::size_t>(instance_concurrency<Kokkos::OpenMP>())
                                 : host_thread_count();
    return per_thread > 0 && points < 2 * per_thread && omp_get_level() == 0 && threads > 1;
  }
#endif
  (void)points;
  (void)saturated;
  return false;
}

void run_with_threads_for(long points, bool saturated, const std::function<void()>& f) {
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
  if constexpr (kPartitions) {
    if (runs_on_one_thread(points, saturated)) {
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
          1, 1);
      omp_set_max_active_levels(levels);
      if (error) std::rethrow_exception(error);
      return;
    }
  }
#endif
  f();
}

}  // namespace lsi
