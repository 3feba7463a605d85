#include "model/concurrent_runs.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <type_traits>
#include <vector>

#if defined(KOKKOS_ENABLE_OPENMP)
#include <omp.h>
#endif

#include "kernels/common/own_stream.hpp"
#include "model/mpm_runner.hpp"  // ensure_kokkos
#include "model/progress.hpp"

namespace lsi {
namespace {

int g_runs_at_once = 0;

// Partitions of the OpenMP backend: Kokkos 3 only (Kokkos 4 removed partition_master). With a
// device, the host's OpenMP threads drive the runs, each on a stream of its own.
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
constexpr bool kPartitions = std::is_same_v<Kokkos::DefaultHostExecutionSpace, Kokkos::OpenMP>;
#else
constexpr bool kPartitions = false;
#endif

}  // namespace

void set_runs_at_once(int runs) { g_runs_at_once = std::max(0, runs); }
int runs_at_once() { return g_runs_at_once; }

int concurrent_runs(std::size_t tasks, int runs) {
  if (!kPartitions || tasks < 2) return 1;
  ensure_kokkos();  // the partitions are Kokkos'; its threads, how many there are
  const int threads = Kokkos::DefaultHostExecutionSpace().concurrency();
  int n = runs > 0 ? std::min(runs, threads) : threads;
  if (g_runs_at_once > 0) n = std::min(n, g_runs_at_once);
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(n, 1)), tasks));
}

double memory_for_runs(std::uint64_t available_bytes) {
  return 0.5 * static_cast<double>(available_bytes);
}

int runs_that_fit(int runs, double run_bytes, std::uint64_t available_bytes) {
  if (available_bytes == 0 || !(run_bytes > 0.0)) return runs;
  const double fit = std::floor(memory_for_runs(available_bytes) / run_bytes);
  return fit >= double(runs) ? runs : std::max(1, static_cast<int>(fit));
}

void run_concurrently(std::size_t tasks, const std::function<void(std::size_t)>& task, int runs,
                      const std::string& progress_label) {
  (void)progress_label;  // where no partitions exist: the runs' own progress lines
  const int partitions = concurrent_runs(tasks, runs);
  std::vector<std::exception_ptr> errors(tasks);
  auto guarded = [&](std::size_t k) {
    try {
      task(k);
    } catch (...) {
      errors[k] = std::current_exception();
    }
  };
  if (partitions < 2) {
    for (std::size_t k = 0; k < tasks; ++k) guarded(k);
  } else {
#if defined(KOKKOS_ENABLE_OPENMP) && KOKKOS_VERSION < 40000
    const int levels = omp_get_max_active_levels();
    omp_set_max_active_levels(std::max(levels, 2));
    std::atomic<std::size_t> next{0};
    const QuietProgress quiet;
    SampleProgress progress(progress_label, tasks, !progress_label.empty(), "runs");
    std::mutex progress_lock;
    std::size_t done = 0;
    Kokkos::OpenMP::partition_master(
        [&](int, int) {
          // On a device, the partition's runs on a stream of its own (own_stream.hpp).
          const OwnStream<Kokkos::DefaultExecutionSpace> stream;
          for (std::size_t k = next++; k < tasks; k = next++) {
            guarded(k);
            const std::lock_guard<std::mutex> lock(progress_lock);
            ++done;
            progress.update(done, done);
          }
        },
        partitions, 1);
    omp_set_max_active_levels(levels);
#endif
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace lsi
